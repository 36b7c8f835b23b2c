#!/usr/bin/perl
# mesh_files.pl DIR — write small mesh files, good and hostile, into DIR:
# the CLI test tests/cli/test_meshes.sh reads them, and make_seeds.sh copies
# them into the fuzz corpus tests/fuzz/corpus/mesh/.
#
#   good-*    meshes every reader must load (a unit square in z = 0, the
#             same in each encoding; a cube with normals, texture coordinates,
#             relative indices): their expected content is stated here, not
#             taken from the loader
#   bad-*     hostile files the loader must refuse in one line, quickly,
#             without crashing, hanging or allocating what the header claims
#
# PLY format: Greg Turk, "The PLY polygon file format" (1994): a text header
# (ply / format / element / property / end_header) and a body of ASCII lines
# or packed binary records (list property = count, then count items).
use strict;
use warnings;

my $dir = shift or die "usage: mesh_files.pl DIR\n";
-d $dir or mkdir $dir or die "mesh_files.pl: cannot create $dir: $!\n";

sub put {
    my ($name, $bytes) = @_;
    open(my $f, '>:raw', "$dir/$name") or die "mesh_files.pl: $dir/$name: $!\n";
    print $f $bytes;
    close($f) or die "mesh_files.pl: $dir/$name: $!\n";
}

# PLY header: format, then [name, count, properties...] per element
sub ply_header {
    my ($format, @elems) = @_;
    my $h = "ply\nformat $format 1.0\ncomment written by tests/fuzz/mesh_files.pl\n";
    for my $e (@elems) {
        my ($name, $count, @props) = @$e;
        $h .= "element $name $count\n";
        $h .= "property $_\n" for @props;
    }
    return $h . "end_header\n";
}
my @xyz = ('float x', 'float y', 'float z');
my @vidx = ('list uchar int vertex_indices');

# the unit square (0,0,0) (1,0,0) (1,1,0) (0,1,0), triangles 012 023
my @sq_v = ([0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]);
my @sq_f = ([0, 1, 2], [0, 2, 3]);
sub bin_body {
    my ($e, $v, $f) = @_;    # $e: '<' little or '>' big endian
    my $b = join '', map { pack("f$e" x 3, @$_) } @$v;
    $b .= join '', map { pack('C', scalar @$_) . pack("l$e" x @$_, @$_) } @$f;
    return $b;
}

put('good-square.obj', "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
put('good-square-crlf.obj', "# CRLF line ends\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf 1 2 3\r\nf -4 -2 -1\r\n");
put('good-square-ascii.ply', ply_header('ascii', ['vertex', 4, @xyz], ['face', 2, @vidx])
    . "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
put('good-square-le.ply', ply_header('binary_little_endian', ['vertex', 4, @xyz], ['face', 2, @vidx])
    . bin_body('<', \@sq_v, \@sq_f));
put('good-square-be.ply', ply_header('binary_big_endian', ['vertex', 4, @xyz], ['face', 2, @vidx])
    . bin_body('>', \@sq_v, \@sq_f));
# a quad face (triangulated by the importer) and a first body byte 0x0a
# (x of vertex 0 is the float with bytes 0a 00 00 00): assimp 5.2 skips a
# 0x0a after "end_header\n" as part of the line end
my $tiny = unpack('f<', pack('L<', 10));
put('good-quad-le.ply', ply_header('binary_little_endian', ['vertex', 4, @xyz], ['face', 1, @vidx])
    . bin_body('<', [[$tiny, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]]));
# a cube, 8 corners, 6 quads, outward normals per face (24 corners), texture coordinates
{
    my @c = map { [($_ & 1) ? 1 : 0, ($_ & 2) ? 1 : 0, ($_ & 4) ? 1 : 0] } 0 .. 7;
    my $o = "# unit cube\nmtllib cube.mtl\no cube\n";
    $o .= sprintf("v %g %g %g\n", @$_) for @c;
    $o .= "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";
    $o .= "vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n";
    my @q = ([0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]);
    $o .= "usemtl grey\ns off\n";
    for my $k (0 .. 5) {
        $o .= 'f ' . join(' ', map { sprintf('%d/%d/%d', $q[$k][$_] + 1, $_ + 1, $k + 1) } 0 .. 3) . "\n";
    }
    put('good-cube.obj', $o);
}

# --- hostile PLY
# the header says 2 vertices, the body holds 4 and 2 faces (face records are
# read from vertex bytes: assimp 5.2 aborted in TriangulateProcess)
put('bad-ply-count-short.ply', ply_header('binary_little_endian', ['vertex', 2, @xyz], ['face', 2, @vidx])
    . bin_body('<', \@sq_v, \@sq_f));
# a correct binary file whose face lists have count 0 (assimp aborted)
put('bad-ply-list-count-zero.ply', ply_header('binary_little_endian', ['vertex', 4, @xyz], ['face', 2, @vidx])
    . bin_body('<', \@sq_v, [[], []]));
# an ASCII grid mesh cut in its body (assimp aborted) and in its header (assimp read forever)
{
    my $n = 12;
    my $b = '';
    for my $j (0 .. $n) { $b .= sprintf("%.6f %.6f %.6f\n", $_ / $n, $j / $n, 0.1 * sin($_ + $j)) for 0 .. $n }
    for my $j (0 .. $n - 1) {
        for my $i (0 .. $n - 1) {
            my $a = $j * ($n + 1) + $i;
            $b .= sprintf("3 %d %d %d\n3 %d %d %d\n", $a, $a + 1, $a + $n + 2, $a, $a + $n + 2, $a + $n + 1);
        }
    }
    my $all = ply_header('ascii', ['vertex', ($n + 1) ** 2, @xyz], ['face', 2 * $n * $n, @vidx]) . $b;
    put('good-grid-ascii.ply', $all);
    put('bad-ply-ascii-truncated.ply', substr($all, 0, int(length($all) * 0.6)));
    put('bad-ply-header-cut.ply', substr($all, 0, 70));
}
# counts the file cannot hold: 20 digits (more than 2^64), 4e9, 2e9 binary, 1e6
put('bad-ply-ascii-count-20digits.ply', ply_header('ascii', ['vertex', '99999999999999999999', @xyz], ['face', 1, @vidx])
    . "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
put('bad-ply-ascii-count-4e9.ply', ply_header('ascii', ['vertex', 4000000000, @xyz], ['face', 1, @vidx])
    . "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
put('bad-ply-binary-count-2e9.ply', ply_header('binary_little_endian', ['vertex', 2000000000, @xyz], ['face', 2000000000, @vidx])
    . bin_body('<', \@sq_v, \@sq_f));
put('bad-ply-binary-1e6-vertices.ply', ply_header('binary_little_endian', ['vertex', 1000000, @xyz], ['face', 2, @vidx])
    . bin_body('<', \@sq_v, \@sq_f));
put('bad-ply-binary-1e6-faces.ply', ply_header('binary_little_endian', ['vertex', 4, @xyz], ['face', 1000000, @vidx])
    . bin_body('<', \@sq_v, \@sq_f));

# --- non-finite and out-of-range coordinates: refused wherever they are
put('bad-obj-nan-late.obj', "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 nan\nf 1 2 3\nf 2 4 3\n");
put('bad-obj-nan-vertex.obj', "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan nan nan\nf 1 2 3\nf 4 2 3\n");
put('bad-obj-inf-unused.obj', "v 0 0 0\nv 1 0 0\nv 0 1 0\nv inf 0 0\nf 1 2 3\n");
put('bad-obj-1e308.obj', "v 1e308 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
put('bad-ply-nan-late.ply', ply_header('ascii', ['vertex', 4, @xyz], ['face', 2, @vidx])
    . "0 0 0\n1 0 0\n0 1 0\n1 1 nan\n3 0 1 2\n3 1 3 2\n");
