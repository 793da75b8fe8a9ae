# methods.gp -- every method placed by its survival edge at a tiny amplitude (x, in units of
# h/c) and its error over time at Table 1's setting (y, log scale): one panel per update order (USL, USF,
# MUSL), a colour per basis and a point shape per velocity transfer; a black cross over a point
# whose run at the survival edge is meaningless (its error over time reached A). Up and left is
# worse.
#
# Reads : datafile (results/methods_data.csv): '#' lines, then the header
#         panel,series,shape,edge_over_cfl,error,meaningless_at_edge
#         (panel 0 usl, 1 usf, 2 musl; series 0..7 the bases mpm, gimp, cpgimp, cpdi, bspline2,
#         bspline3, bspline2 modified, bspline3 modified; shape 0..4 the transfers flip, pic,
#         apic, xpic(2), fmpm(2); meaningless_at_edge 1 where the run at the edge is
#         meaningless). One row per method stable at Table 1's setting with an edge.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "methods.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

sel(p, s, t) = ($1 == p && $2 == s && $3 == t) ? $5 : 1/0
meaningless(p) = ($1 == p && $6 == 1) ? $5 : 1/0

stats datafile using 4 nooutput
xhigh = ceil(STATS_max * 5 + 0.5) / 5.0
stats datafile using (log10($5)) nooutput
ylow = 10**floor(STATS_min)
yhigh = 10**ceil(STATS_max)

array colour[8] = ["#d62728", "#1f77b4", "#6baed6", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"]
array bname[8] = ["mpm", "gimp", "cpgimp", "cpdi", "bspline2", "bspline3", "bspline2 (modified walls)", "bspline3 (modified walls)"]
array shape[5] = [7, 5, 9, 11, 13]
array tname[5] = ["flip", "pic", "apic", "xpic(2)", "fmpm(2)"]
array uname[3] = ["USL", "USF", "MUSL"]

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1500,700 font "DejaVu Sans,11" noenhanced
    } else {
        set terminal svg size 1500,700 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot title "Each method: survival edge at A = 1e-4 against the error over time at Table 1's setting (E = 64, A = 0.015, dt = 1e-4)" . (strlen(subtitle) > 0 ? "\n" . subtitle : "")
    set logscale y
    set format y "%.0e"
    set xrange [0:xhigh]
    set yrange [ylow:yhigh]
    set xlabel "survival edge dt / (h/c)"
    set ylabel "error over time (max over steps and particles)"
    set grid xtics ytics lc rgb "#e0e0e0"
    unset key
    set tmargin at screen 0.86
    set bmargin at screen 0.30
    do for [p = 0:2] {
        set title uname[p + 1]
        # The panels share the y axis; its label, in the first panel only, would cross the frame
        # of the panel on its left in the others.
        if (p > 0) { unset ylabel }
        set lmargin at screen (0.06 + p * 0.32)
        set rmargin at screen (0.34 + p * 0.32)
        plot for [s = 0:7] for [t = 0:4] datafile using 4:(sel(p, s, t)) with points pt shape[t + 1] ps 1.6 lc rgb colour[s + 1], \
             datafile using 4:(meaningless(p)) with points pt 2 ps 2.4 lw 1.5 lc rgb "black"
    }
    unset title
    unset xlabel
    unset ylabel
    unset logscale y
    unset grid
    unset border
    unset tics
    set xrange [0:1]
    set yrange [0:1]
    set lmargin at screen 0.06
    set rmargin at screen 0.97
    set tmargin at screen 0.20
    set bmargin at screen 0.01
    set key center center horizontal maxrows 4 samplen 1 spacing 1.0
    plot for [s = 1:8] NaN with points pt 7 ps 1.6 lc rgb colour[s] title bname[s], \
         for [t = 1:5] NaN with points pt shape[t] ps 1.6 lc rgb "black" title tname[t], \
         NaN with points pt 2 ps 2.4 lw 1.5 lc rgb "black" title "run at the edge meaningless"
    unset multiplot
    unset output
}
