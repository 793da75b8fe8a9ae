# spectral.gp -- the spectral limit of linear MPM and GIMP (USL, FLIP, uniform layout) against
# the particles per cell, in units of h/c, with the measured edge and the CFL number 1, and our
# eq. (108) at 0.95 times the limit, one curve per E (eq. (108) is not dimensionally
# homogeneous: its step in h/c changes with E); one panel per method, log y.
#
# Reads : datafile (results/spectral_data.csv): '#' lines, then the header
#         method,E,ppc,limit,edge,eq108 (method 0 MPM, 1 GIMP; an empty edge: not measured).
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
stats datafile using "eq108" nooutput
ylow = 10 ** floor(log10(STATS_min))
array shade[8] = ["#fdae6b", "#fd8d3c", "#f16913", "#d94801", "#a63603", "#7f2704", "#54278f", "#3f007d"]

do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1300,700 font "sans,11" noenhanced
    } else {
        set terminal svg size 1300,700 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot layout 1,2 title "The spectral limit and eq. (108) against the particles per cell, in units of h/c" . (strlen(subtitle) > 0 ? "\n" . subtitle : "") \
        margins 0.07,0.80,0.11,0.86 spacing 0.07,0.1
    set xlabel "particles per cell"
    set ylabel "c dt / h"
    set xrange [0.5:8.5]
    set xtics 1
    set logscale y
    set yrange [ylow:2]
    set grid
    do for [m = 0:1] {
        set title (m == 0 ? "MPM" : "GIMP")
        if (m == 1) {
            set key at screen 0.99, screen 0.86 right top box opaque
        } else {
            unset key
        }
        # The data rows are in the order of the spec: sorted by ppc for the lines.
        plot 1 with lines lw 2 dt 2 lc rgb "#444444" title "CFL number", \
             datafile using ($1 == m && $2 == firstE ? $3 : 1/0):4 smooth unique with linespoints lw 2 pt 7 ps 1.3 lc rgb "#1f77b4" title sprintf("spectral limit (E = %g)", firstE), \
             datafile using ($1 == m && $2 == firstE ? $3 : 1/0):5 with points pt 6 ps 2.2 lc rgb "#1f77b4" title sprintf("measured edge (E = %g)", firstE), \
             for [k = 1:nE] datafile using ($1 == m && $2 == Es[k] ? $3 : 1/0):6 smooth unique with linespoints lw 1.5 pt 9 ps 1 lc rgb shade[k] title sprintf("eq. (108), E = %g", Es[k])
    }
    unset multiplot
    unset output
}
