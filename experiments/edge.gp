# edge.gp -- the edges in dt against the run length c T (wave passes), in units of h/c: for each method and amplitude the
# survival edge (the largest fixed dt that survives to T; filled markers, solid lines) and the
# accuracy edge (the largest that keeps the error at T within 2 times the smallest dt's; open
# markers, dashed lines), one panel per scene, with h/c (1), a cross where the run at the
# survival edge is meaningless, and beside them, in each series' colour, the scheme's spectral
# limit (dotted) and eq. (108) at the survival edge (dash-dotted); dt on a log scale.
#
# Reads : datafile (results/edge_data.csv): '#' lines (the counts and the cases not drawn, with
#         the reason), then the header
#         panel,series,cT,dt_edge_over_cfl,dt_accurate_over_cfl,meaningless_at_edge,
#         limit_over_cfl,eq108_over_cfl
#         (panel 0 the bar, 1 the second scene; series 1 GIMP A = 0.015, 2 GIMP A = 0.05,
#         3 MPM A = 0.015, 4 MPM A = 0.05, 5 CPDI A = 0.015, 6 CPDI A = 0.05, 7 quadratic
#         B-spline A = 0.015, 8 A = 0.05, 9 cubic B-spline A = 0.015, 10 A = 0.05, as the
#         header's series line lists them); an empty dt_accurate_over_cfl: no accuracy edge; an
#         empty limit_over_cfl or eq108_over_cfl: not measured.
#         One row per drawn case.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "edge.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""
# A subtitle too long for one line (clipped past about 160 characters) is broken after a "; "
# until each line fits.
wrapsub(s) = (strlen(s) <= 150 || strstrt(s, "; ") == 0) ? s : s[1:strstrt(s, "; ")] . "\n" . wrapsub(s[strstrt(s, "; ")+2:])

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

sel(p, s, v) = ($1 == p && $2 == s) ? v : 1/0
cfl(p) = ($1 == p) ? 1 : 1/0
meaningless(p) = ($1 == p && $6 == 1) ? $4 : 1/0

# One y range for both panels, log scale: from the smallest eq. (108) (or edge) to the largest
# spectral limit (or edge), with h/c.
stats datafile using 4 nooutput
edge_min = STATS_min
edge_max = STATS_max
stats datafile using 7 nooutput
top = STATS_max > edge_max ? STATS_max : edge_max
stats datafile using 8 nooutput
bottom = STATS_min < edge_min ? STATS_min : edge_min
ylow = 10 ** floor(log10(bottom))
yhigh = 10 ** (log10(top > 1 ? top : 1) + 0.15)

# Each method in one hue, lighter at A = 0.05.
array colour[10] = ["#1f77b4", "#6baed6", "#d62728", "#ff9896", "#2ca02c", "#98df8a", \
                    "#9467bd", "#c5b0d5", "#8c564b", "#c49c94"]
array filled[10] = [7, 5, 9, 11, 13, 13, 15, 15, 3, 3]
array open[10] = [6, 4, 8, 10, 12, 12, 14, 14, 2, 2]
array name[10] = ["GIMP, A = 0.015", "GIMP, A = 0.05", "MPM, A = 0.015", "MPM, A = 0.05", \
                  "CPDI, A = 0.015", "CPDI, A = 0.05", "B-spline 2, A = 0.015", \
                  "B-spline 2, A = 0.05", "B-spline 3, A = 0.015", "B-spline 3, A = 0.05"]

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1200,900 font "DejaVu Sans,11" noenhanced
    } else {
        set terminal svg size 1200,900 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot title "Survival and accuracy edges against the run length c T, in units of h/c" . (strlen(subtitle) > 0 ? "\n" . wrapsub(subtitle) : "")
    set logscale xy
    set xrange [0.7:150]
    set yrange [ylow:yhigh]
    set format y "%g"
    set xlabel "wave passes c T (T = 1: c T = sqrt(E))"
    set ylabel "dt / (h/c)"
    set grid xtics ytics mxtics lc rgb "#e0e0e0"
    unset key
    set tmargin at screen 0.87
    set bmargin at screen 0.34
    do for [p = 0:1] {
        set title (p == 0 ? "The paper's bar" : "Second scene: Steffen et al. (2008), neo-Hookean")
        set lmargin at screen (p == 0 ? 0.07 : 0.56)
        set rmargin at screen (p == 0 ? 0.48 : 0.97)
        plot datafile using 3:(cfl(p)) with linespoints lw 1.5 pt 1 ps 1.2 lc rgb "black", \
             datafile using 3:(meaningless(p)) with points pt 2 ps 2.6 lw 1.5 lc rgb "black", \
             for [s = 1:10] datafile using 3:(sel(p, s, $4)) with linespoints lw 1.5 pt filled[s] ps 1.2 lc rgb colour[s], \
             for [s = 1:10] datafile using 3:(sel(p, s, $5)) with linespoints lw 1.5 dt 2 pt open[s] ps 1.8 lc rgb colour[s], \
             for [s = 1:10] datafile using 3:(sel(p, s, $7)) with lines lw 1 dt 3 lc rgb colour[s], \
             for [s = 1:10] datafile using 3:(sel(p, s, $8)) with linespoints lw 1 dt 4 pt open[s] ps 0.8 lc rgb colour[s]
    }
    # The legend of both panels, below them.
    unset title
    unset xlabel
    unset ylabel
    unset logscale xy
    unset grid
    unset border
    unset tics
    set xrange [0:1]
    set yrange [0:1]
    set lmargin at screen 0.07
    set rmargin at screen 0.97
    set tmargin at screen 0.25
    set bmargin at screen 0.01
    set key center center horizontal maxrows 8 samplen 3 spacing 1.0
    plot NaN with linespoints lw 1.5 pt 1 ps 1.2 lc rgb "black" title "h/c (speed-of-sound limit)", \
         for [s = 1:10] NaN with linespoints lw 1.5 pt filled[s] ps 1.2 lc rgb colour[s] title "survival edge, " . name[s], \
         NaN with points pt 2 ps 2.6 lw 1.5 lc rgb "black" title "run at the survival edge meaningless", \
         for [s = 1:10] NaN with linespoints lw 1.5 dt 2 pt open[s] ps 1.8 lc rgb colour[s] title "accuracy edge, " . name[s], \
         NaN with lines lw 1 dt 3 lc rgb "black" title "spectral limit (dotted, each series' colour)", \
         NaN with linespoints lw 1 dt 4 pt 6 ps 0.8 lc rgb "black" title "eq. (108) at the survival edge (dash-dotted)"
    unset multiplot
    unset output
    set border
    set tics
    unset key
}
