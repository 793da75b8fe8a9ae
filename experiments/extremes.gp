# extremes.gp -- the verdict of every extremes case in the plane (Courant number, amplitude in
# cells), log-log, one panel per method. Cases at one spot are drawn once: the verdicts of a spot
# side by side (stable, meaningless, unstable, too short to judge, left to right, a fifth of a
# decade apart), the marker growing with the number of cases, and that number printed when it is
# more than 1.
#
# Reads : datafile (results/extremes_data.csv): '#' lines, then the header
#         method,courant,A_over_h,verdict,cases,name
#         (method: its panel, 0..; verdict 0 stable, 1 meaningless, 2 unstable, 3 too short to
#         judge (fewer than 10 steps); name: the method's name, the panel's title).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "extremes.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders

sel(m, v, x) = ($1 == m && $4 == v && $2 > 0 && $3 > 0) ? x : 1/0
# The verdicts of one spot side by side: x shifted by a quarter decade per verdict.
shift(v) = 10 ** ((v - 1.5) * 0.2)
size(n) = 0.9 + 0.6 * log10(n)
many(n) = n > 1 ? sprintf("%d", n) : ""

# The panels and their titles, from the data.
stats datafile using "method" nooutput
panels = int(STATS_max) + 1
array title_of[panels]
do for [m = 1:panels] {
    title_of[m] = ""
    stats datafile using (column("method") == m - 1 ? (title_of[m] = strcol("name"), 0) : 1/0) nooutput
}
rows = panels > 2 ? 2 : 1
cols = int(ceil(panels / real(rows)))

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 550 * cols,(rows == 1 ? 600 : 1000) font "DejaVu Sans,11" noenhanced
    } else {
        face = "sans"
        set terminal svg size 550 * cols,(rows == 1 ? 600 : 1000) dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot layout rows,cols title "Verdicts at the extremes: Courant number against amplitude in cells" . (strlen(subtitle) > 0 ? "\n" . subtitle : "") \
        margins 0.08,0.98,(rows == 1 ? 0.22 : 0.14),(rows == 1 ? 0.86 : 0.91) spacing 0.08,0.09
    set logscale xy
    set format x "%.0e"
    set format y "%.0e"
    set xlabel "Courant number c dt / h"
    set ylabel "amplitude in cells A / h"
    set grid xtics ytics lc rgb "#e0e0e0"
    set xrange [1e-9:1e7]
    set yrange [1e-8:1e5]
    do for [m = 0:panels - 1] {
        set title title_of[m + 1]
        unset key
        plot datafile using (sel(m, 0, $2 * shift(0))):(sel(m, 0, $3)):(size($5)) with points pt 6 ps variable lc rgb "#2ca02c" notitle, \
             datafile using (sel(m, 1, $2 * shift(1))):(sel(m, 1, $3)):(size($5)) with points pt 8 ps variable lc rgb "#ff7f0e" notitle, \
             datafile using (sel(m, 2, $2 * shift(2))):(sel(m, 2, $3)):(size($5)) with points pt 2 ps variable lc rgb "#d62728" notitle, \
             datafile using (sel(m, 3, $2 * shift(3))):(sel(m, 3, $3)):(size($5)) with points pt 4 ps variable lc rgb "#7f7f7f" notitle, \
             datafile using (sel(m, 0, $2 * shift(0))):(sel(m, 0, $3)):(many($5)) with labels offset 0,0.9 font face . ",8" tc rgb "#2ca02c" notitle, \
             datafile using (sel(m, 1, $2 * shift(1))):(sel(m, 1, $3)):(many($5)) with labels offset 0,0.9 font face . ",8" tc rgb "#ff7f0e" notitle, \
             datafile using (sel(m, 2, $2 * shift(2))):(sel(m, 2, $3)):(many($5)) with labels offset 0,0.9 font face . ",8" tc rgb "#d62728" notitle, \
             datafile using (sel(m, 3, $2 * shift(3))):(sel(m, 3, $3)):(many($5)) with labels offset 0,0.9 font face . ",8" tc rgb "#7f7f7f" notitle
    }
    # The key, once for every panel: a plot of nothing across the bottom of the page.
    unset title
    unset logscale
    unset border
    unset tics
    unset grid
    unset xlabel
    unset ylabel
    set xrange [0:1]
    set yrange [0:1]
    set size 1, (rows == 1 ? 0.1 : 0.06)
    set origin 0, 0
    set lmargin 0
    set rmargin 0
    set tmargin 0
    set bmargin 0
    set key center center horizontal maxrows 1 samplen 2 width 2
    plot NaN with points pt 6 lc rgb "#2ca02c" title "stable", \
         NaN with points pt 8 lc rgb "#ff7f0e" title "meaningless (survived, error reached A)", \
         NaN with points pt 2 lc rgb "#d62728" title "unstable", \
         NaN with points pt 4 lc rgb "#7f7f7f" title "too short to judge (< 10 steps)"
    unset multiplot
    unset output
}
