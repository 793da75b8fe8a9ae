# spectral.gp -- the spectral limit of linear MPM and GIMP (USL, FLIP, uniform layout) against
# the particles per cell, in units of h/c, with the measured edge, our eq. (108) bound at the
# same state and the CFL number 1.
#
# Reads : datafile (results/spectral_data.csv): '#' lines, then the header
#         method,ppc,limit,edge,eq108 (method 0 MPM, 1 GIMP; an empty edge: not measured).
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

do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1000,650 font "sans,11" noenhanced
    } else {
        set terminal svg size 1000,650 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set title "The spectral limit against the particles per cell, in units of h/c" . (strlen(subtitle) > 0 ? "\n" . subtitle : "")
    set xlabel "particles per cell"
    set ylabel "c dt / h"
    set xrange [0.5:8.5]
    set xtics 1
    set yrange [0:1.1]
    set grid
    set key right center box opaque
    # The data rows are in the order of the spec (ppc 2 first): sort by ppc for the lines.
    plot 1 with lines lw 2 dt 2 lc rgb "#444444" title "CFL number", \
         datafile using ($1 == 0 ? $2 : 1/0):3 smooth unique with linespoints lw 2 pt 7 ps 1.3 lc rgb "#d62728" title "spectral limit, MPM", \
         datafile using ($1 == 1 ? $2 : 1/0):3 smooth unique with linespoints lw 2 dt 3 pt 5 ps 0.9 lc rgb "#1f77b4" title "spectral limit, GIMP", \
         datafile using ($1 == 0 ? $2 : 1/0):4 with points pt 6 ps 2.2 lc rgb "#d62728" title "measured edge, MPM", \
         datafile using ($1 == 1 ? $2 : 1/0):4 with points pt 4 ps 2.2 lc rgb "#1f77b4" title "measured edge, GIMP", \
         datafile using ($1 == 0 ? $2 : 1/0):5 smooth unique with linespoints lw 2 pt 9 ps 1.3 lc rgb "#ff9896" title "our eq. (108) at the same state, MPM", \
         datafile using ($1 == 1 ? $2 : 1/0):5 smooth unique with linespoints lw 2 pt 11 ps 1.3 lc rgb "#6baed6" title "our eq. (108) at the same state, GIMP"
    unset output
}
