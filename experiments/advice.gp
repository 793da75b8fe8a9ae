# advice.gp -- where the runs of every setting of the advice study passed: one panel per method,
# each setting a point at its Courant number C = c dt/h (x) and its cells (y), marked by the
# longest run length c T/L to which its runs passed (none: the base run is not accurate, C is
# beyond the spectral limit's margin, or its base run fails to both lengths).
#
# Reads : datafile (results/advice_data.csv): the header
#         panel,method,cells,courant,region_cT,error_over_A
#         (panel 0.. one per method, named in column method; region_cT 0 where the setting's
#         runs passed to no length; error_over_A their largest error over time / A, nan where
#         none).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "advice.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders

stats datafile using 1 nooutput
panels = int(STATS_max) + 1
stats datafile using 5 nooutput
longest = STATS_max

sel(p, level) = ($1 == p && (level == 0 ? $5 == 0 : (level == 1 ? ($5 > 0 && $5 < longest) : $5 == longest))) ? $3 : 1/0
# The method's name once per panel, on its first row.
name(p) = ($1 == p && $0 == first[p + 1]) ? strcol(2) : ""
array first[panels]
do for [p = 0:panels - 1] {
    stats datafile using ($1 == p ? $0 : 1/0) nooutput
    first[p + 1] = STATS_min
}

columns = 5
rows = int((panels + columns - 1) / columns)
do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1400,760 font "DejaVu Sans,10" noenhanced
    } else {
        set terminal svg size 1400,760 dynamic font "sans,10" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot title "How far each setting's runs passed, by method" . (strlen(subtitle) > 0 ? "\n" . subtitle : "")
    set logscale xy
    set xrange [0.07:1.5]
    set yrange [18:220]
    set xtics (0.1, 0.25, 0.5, 1)
    set ytics (25, 50, 100)
    set xlabel "C = c dt/h"
    set ylabel "cells"
    set grid xtics ytics lc rgb "#e0e0e0"
    unset key
    height = 0.74 / rows
    do for [p = 0:panels - 1] {
        set origin (p % columns) * 1.0 / columns, 0.16 + (rows - 1 - int(p / columns)) * height
        set size 1.0 / columns, height
        plot datafile using 4:(sel(p, 0)) with points pt 2 ps 1.6 lc rgb "#999999", \
             datafile using 4:(sel(p, 1)) with points pt 9 ps 1.8 lc rgb "#ff7f0e", \
             datafile using 4:(sel(p, 2)) with points pt 7 ps 1.8 lc rgb "#2ca02c", \
             datafile using (0.32):(160):(name(p)) with labels
    }
    # The legend, in the last row.
    unset logscale xy
    unset grid
    unset border
    unset tics
    unset xlabel
    unset ylabel
    set xrange [0:1]
    set yrange [0:1]
    set origin 0, 0
    set size 1, 0.14
    set key center center horizontal
    plot NaN with points pt 7 ps 1.8 lc rgb "#2ca02c" title sprintf("runs passed to c T/L = %g", longest), \
         NaN with points pt 9 ps 1.8 lc rgb "#ff7f0e" title "runs passed to a shorter c T/L only", \
         NaN with points pt 2 ps 1.6 lc rgb "#999999" title "base run did not pass"
    unset multiplot
    unset output
    set border
    set tics
}
