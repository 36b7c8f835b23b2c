# mkexr.pl W H — an uncompressed scanline float RGB OpenEXR of W×H pixels,
# every pixel (1, 1, 1), on stdout (tests/cli: images no shlab command writes)
my ($w, $h) = @ARGV;
sub attr { my ($n, $t, $v) = @_; return "$n\0$t\0" . pack("l<", length $v) . $v; }
my $ch = join("", map { "$_\0" . pack("l<CCCCl<l<", 2, 0, 0, 0, 0, 1, 1) } qw(B G R)) . "\0";
my $hdr = pack("C4", 0x76, 0x2f, 0x31, 0x01) . pack("l<", 2)
  . attr("channels", "chlist", $ch) . attr("compression", "compression", "\0")
  . attr("dataWindow", "box2i", pack("l<4", 0, 0, $w - 1, $h - 1))
  . attr("displayWindow", "box2i", pack("l<4", 0, 0, $w - 1, $h - 1))
  . attr("lineOrder", "lineOrder", "\0") . attr("pixelAspectRatio", "float", pack("f<", 1))
  . attr("screenWindowCenter", "v2f", pack("f<2", 0, 0)) . attr("screenWindowWidth", "float", pack("f<", 1)) . "\0";
my $off = length($hdr) + 8 * $h; my $tab = ""; my $lines = "";
for my $y (0 .. $h - 1) { my $d = pack("f<*", (1) x (3 * $w)); my $l = pack("l<l<", $y, length $d) . $d; $tab .= pack("Q<", $off + length $lines); $lines .= $l; }
binmode STDOUT; print $hdr . $tab . $lines;
