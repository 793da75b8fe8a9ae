# edge.gp -- the stability edge against E (log-log): the largest fixed dt that survives to T for
# each method and amplitude, the speed-of-sound limit h/c, and the eq. (108) bound of the run at
# that dt.
#
# Reads : datafile (results/edge_data.csv): '#' lines, then the header
#         E,method,A,dt_edge,dt_cfl,dt_stable_min_at_edge (method 0 = mpm, 1 = gimp); an empty
#         dt_edge means no dt of the scan survived.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "edge.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

sel(m, a, v) = ($2 == m && abs($3 - a) < 1e-12 && v > 0) ? v : 1/0

do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1000,700 font "sans,11" noenhanced
    } else {
        set terminal svg size 1000,700 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set title "Stability edge against E: largest fixed dt surviving to T = 1, h/c and eq. (108)" . (strlen(subtitle) > 0 ? "\n" . subtitle : "")
    set logscale xy
    set format y "%.0e"
    set xlabel "Young's modulus E (dimensionless model units)"
    set ylabel "time step dt"
    set grid xtics ytics mxtics mytics lc rgb "#e0e0e0"
    set key below horizontal maxcols 3 samplen 3 spacing 1.1
    set xrange [2:20000]
    plot datafile using 1:5 with lines lw 2 lc rgb "black" title "h/c (speed of sound)", \
         datafile using 1:(sel(1, 0.015, $4)) with linespoints pt 7 ps 1.2 lc rgb "#1f77b4" title "dt_edge, GIMP, A = 0.015", \
         datafile using 1:(sel(1, 0.05, $4)) with linespoints pt 5 ps 1.1 lc rgb "#6baed6" title "dt_edge, GIMP, A = 0.05", \
         datafile using 1:(sel(0, 0.015, $4)) with linespoints pt 9 ps 1.3 lc rgb "#d62728" title "dt_edge, MPM, A = 0.015", \
         datafile using 1:(sel(0, 0.05, $4)) with linespoints pt 11 ps 1.3 lc rgb "#ff9896" title "dt_edge, MPM, A = 0.05", \
         datafile using 1:(sel(1, 0.015, $6)) with points pt 6 ps 1.2 lc rgb "#1f77b4" title "eq. (108) at dt_edge, GIMP, A = 0.015", \
         datafile using 1:(sel(1, 0.05, $6)) with points pt 4 ps 1.1 lc rgb "#6baed6" title "eq. (108) at dt_edge, GIMP, A = 0.05", \
         datafile using 1:(sel(0, 0.015, $6)) with points pt 8 ps 1.2 lc rgb "#d62728" title "eq. (108) at dt_edge, MPM, A = 0.015", \
         datafile using 1:(sel(0, 0.05, $6)) with points pt 10 ps 1.2 lc rgb "#ff9896" title "eq. (108) at dt_edge, MPM, A = 0.05"
    unset output
}
