#!/usr/bin/perl
# campaign.pl — a bad-input campaign against the shlab command-line tool:
# generated command lines and mutated input files, each run checked against
# the CLI contract.  Usage:
#
#   tests/fuzz/campaign.pl [--shlab build/san/shlab] [--commands 5000]
#                          [--files 15000] [--seed 1] [--timeout 30] [--log FILE]
#
# Contract (a run that breaks it is a violation, printed with its command):
#   - exit status 0, 1 or 2 (a signal, i.e. a crash, is a violation; a run
#     stopped by the timeout is counted as slow, not as a violation);
#   - exit 2: nothing on stdout and exactly one line on stderr, starting
#     "shlab: error: " (with stdout on /dev/full, whose failure shows only
#     when the result is written, the run's progress and warning lines may
#     precede it: the error line is then the last);
#   - no sanitizer report on stderr (run it with the SANITIZE=1 build);
#   - no temporary file (*.tmp.*) left; after an exit 2, no new file and the
#     pre-existing files (used as --out / --emit-candidate targets) unchanged.
# Some runs write stdout to /dev/full: those must fail with exit 2.
# Ends with one line "campaign: N runs, V violations, S slow" and exits 1 if
# V > 0.  Perl only (Debian's perl-base), no modules beyond the core.
use strict;
use warnings;
use POSIX ();
use File::Temp qw(tempdir);
use Digest::MD5 qw(md5_hex);
use Getopt::Long;

my ($shlab, $ncmd, $nfile, $seed, $timeout, $logf) = ('build/san/shlab', 5000, 15000, 1, 30, '');
GetOptions('shlab=s' => \$shlab, 'commands=i' => \$ncmd, 'files=i' => \$nfile,
           'seed=i' => \$seed, 'timeout=i' => \$timeout, 'log=s' => \$logf) or die "campaign: bad options\n";
-x $shlab or die "campaign: $shlab is not built\n";
srand($seed);
$ENV{ASAN_OPTIONS} = 'detect_leaks=1:abort_on_error=0:exitcode=99';
$ENV{UBSAN_OPTIONS} = 'print_stacktrace=1:halt_on_error=1:exitcode=98';
my $W = tempdir('shlab_campaign.XXXXXX', TMPDIR => 1, CLEANUP => 1);
my $LOG;
if ($logf) { open $LOG, '>', $logf or die "campaign: $logf: $!\n"; }

# ---- fixed inputs --------------------------------------------------------------
my $corpus = 'tests/fuzz/corpus';
my @exr   = glob("$corpus/exr/*.exr");
my @fixt  = (glob("$corpus/fixture/*.json"));
my @cand  = glob("$corpus/candidate/*.json");
my @coef  = glob("$corpus/coeffs/*");
mkdir "$W/dir";
sub put { my ($p, $s) = @_; open my $f, '>', $p or die; binmode $f; print $f $s; close $f; }
sub slurp { my $p = shift; open my $f, '<', $p or return ''; binmode $f; local $/; my $s = <$f>; close $f; return $s; }
put("$W/existing.exr", "pre-existing file\n");
put("$W/existing.json", "{\"pre\":\"existing\"}\n");
put("$W/c4.json", "{\"coeffs\":[1,0.5,0.25,0.125]}");
put("$W/c9.txt", "1 0 0 0 0.5 0 0 0 0.25");
put("$W/cand.json", slurp("$corpus/candidate/good.json"));
my $fx_small = "$corpus/fixture/orders_1_3.json";

sub pick { return $_[int(rand(@_))]; }

# ---- values: good ones, and the bad ones the campaign is about -----------------
my @bad = ('', '-1', '0', '2050', '1e-400', '1e999', '-0', 'nan', 'inf', '-inf', '0x10', '1e308',
           "x\ny", "\x{ff}\x{fe}", "\e[31m", "2147483648", "4294967297", "-2147483649", '1,2',
           '1,,2', ' 3', '3 ', '+3', '3.5', 'a', '--order', '-', '%s%n', 'x' x 5000,
           '/nonexistent/x', "$W/dir", '/dev/null', '/dev/full', "$W/existing.exr", "$W/existing.json");
my %good = (
    order => ['1', '2', '3', '4', '8', '16'], bigorder => ['64', '200', '1000', '2049'],
    light => ['green', 'cap:0.5', 'cap:90', 'cie-overcast', 'cie-clear:0.3,1', 'cie-partly:1,2',
              'const:1', 'lobe:2', 'cap:4', 'lobe:-1', 'cap:', 'cie-clear:1', 'cap:1e-400', 'sun'],
    method_rot => ['ivanic', 'zxzxz', 'choi', 'blanco', 'wigner', 'reference', 'z', 'taylor1',
                   'taylor1.5', 'taylor2', 'nope'],
    method_proj => ['quad', 'mc', 'random', 'qmc', 'nope'],
    num => ['0', '0.5', '1', '-1', '3.14159', '90', '1e-3', '100', '-45'],
    vec3 => ['0,0,1', '1,0,0', '0,0,0', '1,2', '1,2,3,4', '0.6,0,0.8', 'a,b,c'],
    euler => ['0.1,0.2,0.3', '30,60,-45', '0,0,0', '1,2', '0,3.14159265358979,0'],
    quat => ['1,0,0,0', '0,0,0,0', '0.5,0.5,0.5,0.5', '1,2,3'],
    matrix => ['1,0,0,0,1,0,0,0,1', '0,-1,0,1,0,0,0,0,1', '1,1,1,1,1,1,1,1,1', '1,0,0'],
    coeffs => ['1,0.5,0,0', '1', '1,2,3', '1 0 0 0 0 0 0 0 0', '[1,0,0,0]', '1,1e-400,0,0'],
    window => ['none', 'gauss:0.01', 'hann', 'hann:3', 'lanczos:2', 'gauss', 'hann:-1'],
    format => ['table', 'csv', 'json', 'xml'],
    conv => ['cs', 'nocs', 'CS'], norm => ['cs', 'nocs', '4pi', 'schmidt', 'x'],
    prec => ['double', 'float', 'half'], family => ['linear', 'cone', 'midrange', 'x'],
    infile => [\@coef, "$W/c4.json", "$W/c9.txt", '/nonexistent', "$W/dir"],
    exrfile => [\@exr, '/nonexistent.exr', "$W/existing.json"],
    fixture => [\@fixt, '/nonexistent.json'],
    candfile => [\@cand, "$W/cand.json"],
    outexr => ["$W/out.exr", "$W/existing.exr", "$W/dir", '/nonexistent/o.exr', "$W/dir/o.exr"],
    outjson => ["$W/e.json", "$W/existing.json", "$W/dir"],
    outdir => ["$W/dir", "$W/fx", '/nonexistent/d', "$W/existing.json"],
    int => ['1', '2', '10', '100', '0', '-5', '1000000'],
    layout => ['latlong', 'probe', 'x'], mode => ['per-rotation', 'batched', 'both', 'x'],
);

# command → options (option => value kind; '' for a flag)
my $rot = {euler => 'euler', quat => 'quat', matrix => 'matrix', axis => 'vec3', angle => 'num',
           inverse => '', orthonormalize => '', degrees => ''};
my %cmds = (
    eval => {order => 'order', dir => 'vec3', theta => 'num', phi => 'num', degrees => '', convention => 'conv'},
    project => {order => 'order', light => 'light', method => 'method_proj', samples => 'int', seed => 'int',
                degrees => '', exr => 'exrfile', layout => 'layout', convention => 'conv'},
    reconstruct => {order => 'order', coeffs => 'coeffs', in => 'infile', out => 'outexr', width => 'int',
                    window => 'window', convention => 'conv'},
    triple => {order => 'order', light => 'light', degrees => '', convention => 'conv'},
    convert => {from => 'norm', to => 'norm', coeffs => 'coeffs', in => 'infile'},
    rotmat => {%$rot, order => 'order', band => 'int', method => 'method_rot', precision => 'prec', convention => 'conv'},
    rotate => {%$rot, coeffs => 'coeffs', in => 'infile', order => 'order', method => 'method_rot',
               precision => 'prec', convention => 'conv'},
    euler => {%$rot, convention => 'conv'},
    stability => {method => 'method_rot', lmax => 'order', bands => 'coeffs', precision => 'prec', quiet => ''},
    fixtures => {out => 'outdir', method => 'method_rot', quiet => ''},
    verify => {fixture => 'fixture', candidate => 'candfile', method => 'method_rot', precision => 'prec',
               diagnose => '', 'emit-candidate' => 'outjson', simulate => 'method_rot'},
    scale => {order => 'order', family => 'family', k => 'num', energy => '', 'cone-angle' => 'num',
              degrees => '', verify => '', convention => 'conv'},
    'scale-interp' => {order => 'order', family => 'family', samples => 'int', kmin => 'num', kmax => 'num',
                       quiet => ''},
    'scale-scene' => {scene => 'family', order => 'order', k => 'num', probe => 'exrfile', light => 'light'},
    deriv => {order => 'order', k => 'int', beta => 'num', degrees => ''},
    'taylor-error' => {order => 'order', taylor => 'num', beta => 'num', 'beta-max' => 'num', quiet => '',
                       degrees => ''},
    bench => {order => 'coeffs', methods => 'method_rot', mode => 'mode', count => 'int', repeat => 'int',
              quiet => ''},
    plan => {order => 'order', 'max-beta' => 'num', tolerance => 'num', exr => 'exrfile', quiet => '',
             degrees => ''},
);

sub value {
    my $kind = shift;
    return pick(@bad) if rand() < 0.25;
    my $v = pick(@{$good{$kind}});
    $v = pick(@$v) if ref $v eq 'ARRAY';
    $v = pick(@{$good{bigorder}}) if $kind eq 'order' && rand() < 0.03;
    return $v;
}

sub gen_command {
    my $c = pick(keys %cmds);
    $c = pick('nope', '--version', '--help', '') if rand() < 0.01;
    my @a = ($c);
    my @opts = keys %{$cmds{$c} || {}};
    my $n = int(rand(6)) + 1;
    for (1 .. $n) {
        my $o = rand() < 0.05 ? pick('bogus', 'help', 'format') : pick(@opts, 'format');
        next unless defined $o;
        my $kind = $o eq 'format' ? 'format' : ($cmds{$c}{$o} // 'num');
        my $style = rand();
        if ($kind eq '') { push @a, "--$o"; }
        elsif ($style < 0.1) { push @a, "--$o=" . value($kind); }
        elsif ($style < 0.13) { push @a, "--$o"; }   # value missing
        else { push @a, "--$o", value($kind); }
        push @a, $a[-1] if rand() < 0.03;           # stray repeat of the last word
    }
    push @a, pick(@bad) if rand() < 0.03;           # a stray argument
    push @a, '--quiet' if ($c eq 'bench' || $c eq 'fixtures') && rand() < 0.5;
    return \@a;
}

# ---- running and judging one command ---------------------------------------------
my ($runs, $viol, $slow, $cur_full) = (0, 0, 0, 0);
my %kinds;

sub listing {
    my @f;
    for my $d ($W, "$W/dir", "$W/fx") {
        opendir(my $h, $d) or next;
        push @f, map { "$d/$_" } grep { !/^\.\.?$/ } readdir $h;
        closedir $h;
    }
    return { map { $_ => (-f $_ ? md5_hex(slurp($_)) : 'dir') } @f };
}

sub report {
    my ($why, $args) = @_;
    $viol++;
    $kinds{$why}++;
    my $cmd = join(' ', map { my $s = $_; $s =~ s/([^\x20-\x7e])/sprintf('\\x%02x', ord $1)/ge;
                              length($s) > 80 ? substr($s, 0, 80) . '...' : $s } @$args);
    $cmd .= ' >/dev/full' if $cur_full;
    print "VIOLATION ($why): shlab $cmd\n";
    print $LOG "VIOLATION ($why): shlab $cmd\n" if $LOG;
}

sub run_one {
    my ($args, $full) = @_;
    $cur_full = $full;
    $runs++;
    my $before = listing();
    my $pid = fork();
    die "fork: $!" unless defined $pid;
    if (!$pid) {
        open STDIN, '<', '/dev/null';
        open STDOUT, '>', $full ? '/dev/full' : "$W/.stdout";
        open STDERR, '>', "$W/.stderr";
        chdir $W;
        { no warnings 'exec'; exec { $shlab =~ m{^/} ? $shlab : "$ENV{PWD}/$shlab" } 'shlab', @$args; }
        POSIX::_exit(127);
    }
    my $st;
    eval {
        local $SIG{ALRM} = sub { die "timeout\n" };
        alarm $timeout;
        waitpid($pid, 0);
        $st = $?;
        alarm 0;
    };
    if ($@) {
        kill 'TERM', $pid;
        waitpid($pid, 0);
        $slow++;
        print $LOG "SLOW: shlab @$args\n" if $LOG;
        # cleanup after the signal is part of the contract
        report('temporary left after SIGTERM', $args) if grep { /\.tmp\./ } keys %{listing()};
        system('rm', '-rf', "$W/fx", "$W/out.exr", "$W/e.json", "$W/dir");
        mkdir "$W/dir";
        return;
    }
    my $err = slurp("$W/.stderr");
    my $out = $full ? '' : slurp("$W/.stdout");
    my ($code, $sig) = ($st >> 8, $st & 127);
    if ($sig) { report("killed by signal $sig", $args); }
    elsif ($code == 99 || $code == 98 || $err =~ /Sanitizer|runtime error:/) { report('sanitizer report', $args); }
    elsif ($code > 2) { report("exit $code", $args); }
    elsif ($code == 2) {
        my @lines = split /\n/, $err, -1;
        pop @lines if @lines && $lines[-1] eq '';
        report('stdout not empty on exit 2', $args) if length $out;
        # stdout on /dev/full fails only when the result is written, after the
        # work: the progress and warning lines of that work ("bench: ...") may
        # precede the one error line, which must then be the last line
        my $one = @lines == 1 && $lines[0] =~ /^shlab: error: /;
        $one ||= $full && @lines > 1 && $lines[-1] =~ /^shlab: error: /
                 && !grep { !/^[a-z][a-z-]*: / || /^shlab: error: / } @lines[0 .. $#lines - 1];
        report('not exactly one error line', $args) unless $one;
    } elsif ($full && $code == 0) {
        report('exit 0 with stdout on /dev/full', $args);
    }
    my $after = listing();
    report('temporary file left', $args) if grep { /\.tmp\./ } keys %$after;
    if ($code == 2 && !$sig) {
        for my $f (keys %$after) {
            next if $f =~ m{/\.std(out|err)$};
            report('file left after a failure', $args) unless exists $before->{$f};
        }
        for my $f (keys %$before) {
            next if $f =~ m{/\.std(out|err)$};
            report('pre-existing file changed or removed', $args)
                unless exists $after->{$f} && $after->{$f} eq $before->{$f};
        }
    }
    # back to the starting state
    system('rm', '-rf', "$W/fx", "$W/out.exr", "$W/e.json", "$W/dir");
    mkdir "$W/dir";
    put("$W/existing.exr", "pre-existing file\n");
    put("$W/existing.json", "{\"pre\":\"existing\"}\n");
}

# ---- 1. generated command lines ----------------------------------------------------
for my $i (1 .. $ncmd) {
    run_one(gen_command(), rand() < 0.1);
    print STDERR "campaign: $i of $ncmd command lines, $viol violations\n" if $i % 500 == 0;
}
my $cmd_runs = $runs;

# ---- 2. mutated input files ----------------------------------------------------------
sub mutate {
    my $s = shift;
    my $n = length $s;
    return $s unless $n;
    my $k = 1 + int(rand(8));
    for (1 .. $k) {
        my $r = rand();
        $n = length $s;
        last unless $n;
        my $p = int(rand($n));
        if ($r < 0.35) { substr($s, $p, 1) = chr(ord(substr($s, $p, 1)) ^ (1 << int(rand(8)))); }
        elsif ($r < 0.55) { substr($s, $p, 1) = chr(pick(0, 0xff, 0x7f, 0x80, int(rand(256)))); }
        elsif ($r < 0.65) { substr($s, $p, 4) = pack('l<', pick(0, -1, 0x7fffffff, -0x80000000, 32768, int(rand(2**31)))); }
        elsif ($r < 0.75) { $s = substr($s, 0, $p); }                                 # truncate
        elsif ($r < 0.82) { substr($s, $p, 0) = substr($s, int(rand($n)), int(rand(64))); } # duplicate
        elsif ($r < 0.88) { substr($s, $p, int(rand(64))) = ''; }                     # delete
        elsif ($r < 0.94) { substr($s, $p, 0) = pick("\n", "\0", "1e-400", "99999999999999999999", '"', '{', ']', "\xc3"); }
        else { substr($s, $p, 1) = pick('0', '9', '-', '.', 'e', ',', ' '); }
    }
    return $s;
}

my @targets = (
    [\@exr, sub { ['project', '--order', pick(1, 2, 4), '--exr', $_[0], pick('--layout', '--format'), pick('latlong', 'probe', 'json')] }],
    [\@exr, sub { ['plan', '--order', 'auto', '--exr', $_[0], '--tolerance', '0.1', '--max-beta', '0.1', '--quiet'] }],
    [\@exr, sub { ['scale-scene', '--scene', 'sphere', '--order', '3', '--k', '0.5', '--probe', $_[0]] }],
    [\@fixt, sub { ['verify', '--fixture', $_[0], '--method', pick('ivanic', 'zxzxz', 'blanco'), '--emit-candidate', pick("$W/e.json", "$W/existing.json")] }],
    [\@cand, sub { ['verify', '--fixture', $fx_small, '--candidate', $_[0], pick('--diagnose', '--format=csv')] }],
    [\@coef, sub { ['reconstruct', '--order', pick(1, 2), '--in', $_[0], '--width', '8', '--out', pick("$W/out.exr", "$W/existing.exr")] }],
    [\@coef, sub { ['convert', '--in', $_[0], '--from', 'cs', '--to', pick('nocs', 'schmidt')] }],
    [\@coef, sub { ['rotate', '--in', $_[0], '--method', 'ivanic', '--euler', '0.1,0.2,0.3'] }],
);
my @fxcand = glob("$corpus/candidate/*.json");
for my $i (1 .. $nfile) {
    my $t = $targets[int(rand(@targets))];
    my $src = pick(@{$t->[0]});
    my $ext = $src =~ /\.(\w+)$/ ? $1 : 'txt';
    my $m = "$W/mutated.$ext";
    put($m, mutate(slurp($src)));
    run_one($t->[1]->($m), rand() < 0.05);
    unlink $m;
    print STDERR "campaign: $i of $nfile mutated files, $viol violations\n" if $i % 1000 == 0;
}

my $file_runs = $runs - $cmd_runs;
print "campaign: $cmd_runs command lines, $file_runs mutated files: $runs runs, $viol violations, $slow slow (stopped after ${timeout} s)\n";
print "campaign: violations by kind: ", join(', ', map { "$_: $kinds{$_}" } sort keys %kinds), "\n" if $viol;
print $LOG "campaign: $runs runs, $viol violations, $slow slow\n" if $LOG;
exit($viol ? 1 : 0);
