# scenes.gp -- per scene, at the scenes study's reference Courant number, one series per method:
# above, the error over time against the exact solution; below, the displacement of the body's
# last particle (its free end) against time, beside the exact one.
#
# Reads : datafile (results/scenes_data.csv): '#' lines, then the header
#         panel,series,scene,method,t,error_over_A,tip_over_A,tip_exact_over_A and one row per
#         drawn step. panel: 0.. per scene; series: 0.. per method (alphabetical);
#         error_over_A: max_p |u_p - u(X_p, t)| per the scene's displacement scale A;
#         tip_over_A, tip_exact_over_A: x_p - X_p of the last particle and the exact u(X_p, t).
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

set grid
# One key per row, in the first panel (every panel draws the same methods), where its curves
# leave room: bottom right above (the errors start small), bottom left below (the free ends
# start at rest or rise).

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [format in "png svg"] {
    if (format eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 1800,900 font "DejaVu Sans,10" noenhanced
    } else {
        face = "Arial"
        set terminal svg size 1800,900 font "Arial,10" noenhanced background "white"
    }
    set output outbase . "." . format
    set multiplot layout 2, panels title "Per scene and method: the error against the exact solution over time (above) and the free end's displacement beside the exact one (below) (" . subtitle . ")"
    set xlabel "t"
    set ylabel "error / A"
    set logscale y
    set format y "%.0e"
    do for [k = 1:panels] {
        set title scenes[k]
        if (k == 1) { set key bottom right font face . ",9" } else { unset key }
        plot for [s = 1:nseries] datafile \
            using (column("panel") == k - 1 && column("series") == s - 1 ? column("t") : 1/0):"error_over_A" \
            with lines lw 1.5 title names[s]
    }
    unset logscale y
    set format y "%g"
    set ylabel "last particle's u / A"
    do for [k = 1:panels] {
        set title scenes[k] . ": free end"
        if (k == 1) { set key bottom left font face . ",9" } else { unset key }
        plot for [s = 1:nseries] datafile \
            using (column("panel") == k - 1 && column("series") == s - 1 ? column("t") : 1/0):"tip_over_A" \
            with lines lw 1.5 title names[s], \
            datafile using (column("panel") == k - 1 && column("series") == 0 ? column("t") : 1/0):"tip_exact_over_A" \
            with lines lw 2 dt 2 lc rgb "black" title "exact"
    }
    unset multiplot
    unset output
}
