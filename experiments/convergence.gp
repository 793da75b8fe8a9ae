# convergence.gp -- the error over time against h, log-log, one panel per E, one series per basis.
#
# Reads : datafile (results/convergence_data.csv): '#' lines, then the header
#         E,panel,series,method,h,error_over_time and one row per stable run of the h sweep. panel: 0.. per
#         E; series: 0.. per basis (alphabetical).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional: the runs drawn and left out).

if (!exists("datafile") || !exists("outbase")) {
    print "convergence.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders

stats datafile using "panel" nooutput
panels = int(STATS_max) + 1
stats datafile using "series" nooutput
nseries = int(STATS_max) + 1
array panel_E[panels]
do for [k = 1:panels] {
    stats datafile using (column("panel") == k - 1 ? column("E") : 1/0) nooutput
    panel_E[k] = STATS_min
}
array names[nseries]
do for [s = 1:nseries] {
    names[s] = ""
}
# The basis of each series, from the method column (strings are read row by row).
do for [s = 1:nseries] {
    stats datafile using (column("series") == s - 1 ? (names[s] = strcol("method"), 0) : 1/0) nooutput
}

set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "h"
set ylabel "error over time (max over steps and particles)"
set grid
# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [format in "png svg"] {
    if (format eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 1500,500 font "DejaVu Sans,10"
    } else {
        face = "Arial"
        set terminal svg size 1500,500 font "Arial,10"
    }
    set key bottom right font face . ",9"
    set output outbase . "." . format
    set multiplot layout 1, panels title "Error over time against h, every method (" . subtitle . ")"
    do for [k = 1:panels] {
        set title sprintf("E = %g", panel_E[k])
        plot for [s = 1:nseries] datafile \
            using (column("panel") == k - 1 && column("series") == s - 1 ? column("h") : 1/0):"error_over_time" \
            with linespoints pt (s + 3) title names[s]
    }
    unset multiplot
    set output
}
