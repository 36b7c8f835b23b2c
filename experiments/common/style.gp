# style.gp — one look for every plot (loaded by the experiments' scripts):
# each rotation method keeps its colour, point type and dash type in every
# figure; exact methods are solid, the Taylor approximations dashed.
# Colours: Tableau 10 (distinguishable, and not only by hue: lightness varies).
set terminal pngcairo size 1400,520 enhanced font ",11"
set grid lc rgb "#dddddd"
set border lc rgb "#444444"
mname = "z ivanic zxzxz choi blanco wigner reference taylor1 taylor1.5 taylor2 zxzxz_dense matrix_to_angles halfpi"
mcols = "#4E79A7 #F28E2B #E15759 #76B7B2 #59A14F #B07AA1 #7F7F7F #9C755F #000000 #D37295 #555555 #999999 #B6992D"
mpts  = "4 5 7 9 11 13 1 6 8 10 3 2 15"
mdts  = "1 1 1 1 1 1 1 2 2 2 3 4 1"
midx(m) = sum [k=1:words(mname)] (word(mname, k) eq m ? k : 0)
mcol(m) = word(mcols, midx(m) > 0 ? midx(m) : 7)
mpt(m) = int(word(mpts, midx(m) > 0 ? midx(m) : 7))
mdt(m) = int(word(mdts, midx(m) > 0 ? midx(m) : 7))
mlab(m) = m eq "zxzxz_dense" ? "zxzxz, dense X (test)" : m eq "matrix_to_angles" ? "matrix → angles alone" : m
