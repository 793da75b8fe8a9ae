# spectral.gp -- linear MPM and GIMP (USL, FLIP, uniform layout) against the particles per cell:
# left, the spectral limit in units of h/c (the same at every E) with the measured edge and the
# CFL number 1; right, our eq. (108) at 0.95 times the limit divided by the limit, one curve per
# E (eq. (108) is not dimensionally homogeneous: its ratio to the limit changes with E), GIMP as
# lines, MPM as open circles, and the limit itself (ratio 1); log y.
#
# Reads : datafile (results/spectral_data.csv): '#' lines, then the header
#         method,E,ppc,limit,edge,eq108,ratio (method 0 MPM, 1 GIMP; an empty edge: not measured).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "spectral.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

# The values of E, in increasing order, from the data.
array Es[16]
nE = 0
last = 0
do for [k = 1:16] {
    stats datafile using (column("E") > last ? 1 : 0) nooutput
    if (STATS_sum > 0) {
        stats datafile using (column("E") > last ? column("E") : 1/0) nooutput
        nE = nE + 1
        Es[nE] = STATS_min
        last = STATS_min
    }
}
firstE = Es[1]
stats datafile using "ratio" nooutput
ratio_low = STATS_min / 1.6
stats datafile using "limit" nooutput
limit_low = STATS_min - 0.15
stats datafile using "ppc" nooutput
ppc_high = STATS_max
array shade[8] = ["#fdae6b", "#fd8d3c", "#f16913", "#d94801", "#a63603", "#7f2704", "#54278f", "#3f007d"]

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1300,720 font "DejaVu Sans,11" noenhanced
    } else {
        set terminal svg size 1300,720 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot layout 1,2 title "The spectral limit, and eq. (108) divided by it, against the particles per cell" . (strlen(subtitle) > 0 ? "\n" . subtitle : "") \
        margins 0.06,0.81,0.10,0.85 spacing 0.08,0.1
    set xlabel "particles per cell"
    set xrange [0.5:ppc_high + 0.5]
    set xtics 1
    set grid

    # Left: the limit and the measured edge, in c dt / h.
    set title sprintf("The spectral limit (the same at every E) and the edge at E = %g", firstE)
    set ylabel "c dt / h"
    unset logscale y
    set yrange [limit_low:1.1]
    set ytics autofreq
    set key bottom right box opaque
    plot 1 with lines lw 2 dt 2 lc rgb "#444444" title "CFL number", \
         datafile using ($1 == 0 && $2 == firstE ? $3 : 1/0):4 smooth unique with linespoints lw 2 pt 7 ps 1.2 lc rgb "#1f77b4" title "MPM, spectral limit", \
         datafile using ($1 == 1 && $2 == firstE ? $3 : 1/0):4 smooth unique with linespoints lw 2 dt 3 pt 5 ps 0.7 lc rgb "#2ca02c" title "GIMP, spectral limit", \
         datafile using ($1 == 0 && $2 == firstE ? $3 : 1/0):5 with points pt 6 ps 2.4 lc rgb "#1f77b4" title "MPM, measured edge", \
         datafile using ($1 == 1 && $2 == firstE ? $3 : 1/0):5 with points pt 4 ps 1.8 lc rgb "#2ca02c" title "GIMP, measured edge"

    # Right: eq. (108) / limit, one curve per E.
    set title "Eq. (108) divided by the spectral limit, one curve per E"
    set ylabel "eq. (108) / spectral limit"
    set logscale y
    set yrange [ratio_low:1.6]
    set ytics (0.02, 0.05, 0.1, 0.2, 0.5, 1)
    set key at screen 0.99, screen 0.85 right top box opaque
    plot 1 with lines lw 2 lc rgb "#1f77b4" title "the limit (ratio 1)", \
         for [k = nE:1:-1] datafile using ($1 == 1 && $2 == Es[k] ? $3 : 1/0):7 smooth unique with linespoints lw 1.5 pt 9 ps 1 lc rgb shade[k] title sprintf("GIMP, E = %g", Es[k]), \
         for [k = nE:1:-1] datafile using ($1 == 0 && $2 == Es[k] ? $3 : 1/0):7 with points pt 6 ps 1.8 lc rgb shade[k] notitle, \
         NaN with points pt 6 ps 1.8 lc rgb "#444444" title "MPM (same colours)"
    unset multiplot
    unset output
}
