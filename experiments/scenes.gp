# scenes.gp -- the error over time against the exact solution, one panel per scene, one series
# per method, at the scenes study's reference Courant number.
#
# Reads : datafile (results/scenes_data.csv): '#' lines, then the header
#         panel,series,scene,method,t,error_over_A and one row per drawn step. panel: 0.. per
#         scene; series: 0.. per method (alphabetical); error_over_A: max_p |u_p - u(X_p, t)|
#         per the scene's displacement scale A.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "scenes.gp: datafile and outbase must be set"
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
array scenes[panels]
array names[nseries]
do for [k = 1:panels] {
    scenes[k] = ""
    stats datafile using (column("panel") == k - 1 ? (scenes[k] = strcol("scene"), 0) : 1/0) nooutput
}
do for [s = 1:nseries] {
    names[s] = ""
    stats datafile using (column("series") == s - 1 ? (names[s] = strcol("method"), 0) : 1/0) nooutput
}

set xlabel "t"
set ylabel "error / A"
set logscale y
set format y "%.0e"
set grid
set key top left font ",9"

do for [format in "png svg"] {
    if (format eq "png") {
        set terminal pngcairo size 1800,500 font "Arial,10" noenhanced
    } else {
        set terminal svg size 1800,500 font "Arial,10" noenhanced background "white"
    }
    set output outbase . "." . format
    set multiplot layout 1, panels title "Error against the exact solution over time, per scene and method (" . subtitle . ")"
    do for [k = 1:panels] {
        set title scenes[k]
        plot for [s = 1:nseries] datafile \
            using (column("panel") == k - 1 && column("series") == s - 1 ? column("t") : 1/0):"error_over_A" \
            with lines lw 1.5 title names[s]
    }
    unset multiplot
    unset output
}
