# variants.gp -- per variant of the implementation choices, ours / paper of Table 1's max error
# in every cell where both are stable: one point per cell (MPM left, GIMP right of the variant's
# tic, spread a little so that equal values stay visible), a bar at each median, the line at 1
# and the band of agreement within a factor 3; log y.
#
# Reads : datafile (results/variants_data.csv): '#' lines, then x,method,kind,ratio,variant
#         (x the variant's position; method 0 mpm, 1 gimp; kind 0 one cell, 1 a median, 2 the
#         variant's tic).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "variants.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders

offset(m) = (m == 0 ? -0.2 : 0.2)
# A deterministic spread of +-0.09 by row number.
spread(row) = 0.18 * ((row * 0.6180339887) - floor(row * 0.6180339887) - 0.5)
cell(m, x) = ($3 == 0 && $2 == m && $4 > 0) ? x : 1/0
med(m, x) = ($3 == 1 && $2 == m && $4 > 0) ? x : 1/0

stats datafile using 1 nooutput
nvariants = STATS_max

# A long subtitle would be clipped at 1400 px: break it after "; " (or else after the last ", "
# within the first 150 characters).
# lastcomma(s): position of the last ", " in s (0 if none).
lastcomma(s) = (strstrt(s, ", ") == 0) ? 0 : strstrt(s, ", ") + lastcomma(s[strstrt(s, ", ")+1:])
wrapsub(s) = (strlen(s) <= 150) ? s : \
             (strstrt(s, "; ") > 0) ? s[1:strstrt(s, "; ")] . "\n" . s[strstrt(s, "; ")+2:] : \
             (lastcomma(s[1:150]) > 0) ? s[1:lastcomma(s[1:150])] . "\n" . s[lastcomma(s[1:150])+2:] : s

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 1400,800 font "DejaVu Sans,11" noenhanced
    } else {
        face = "sans"
        set terminal svg size 1400,800 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set title "Our max error / the paper's, per Table 1 cell where both are stable, under each implementation choice" . (strlen(subtitle) > 0 ? "\n" . wrapsub(subtitle) : "")
    set lmargin 12
    set rmargin 9
    set bmargin 9
    set logscale y
    set format y "%.0e"
    set ylabel "max error, ours / paper"
    set xrange [0.4:nvariants + 0.6]
    set yrange [*:*]
    set xtics rotate by -40 left nomirror scale 0 font face . ",11"
    set grid ytics lc rgb "#e0e0e0"
    # A light line between variants.
    do for [i = 1:nvariants - 1] {
        set arrow (10 + i) from i + 0.5, graph 0 to i + 0.5, graph 1 nohead lc rgb "#d8d8d8" back
    }
    set object 1 rect from graph 0, first 1.0/3 to graph 1, first 3 fc rgb "#dcefdc" fs solid 1.0 noborder behind
    set arrow 1 from graph 0, first 1 to graph 1, first 1 nohead lc rgb "#2ca02c" lw 1.5 front
    set tmargin 5
    set key at screen 0.5, screen 0.015 center bottom horizontal maxrows 1 samplen 2 spacing 1.2
    plot datafile using 1:(1/0):xtic($3 == 2 ? strcol(5) : "") with points notitle, \
         datafile using (cell(0, $1 + offset(0) + spread($0))):(cell(0, $4)) with points pt 6 ps 0.9 lc rgb "#d62728" title "MPM cell", \
         datafile using (cell(1, $1 + offset(1) + spread($0))):(cell(1, $4)) with points pt 4 ps 0.9 lc rgb "#1f77b4" title "GIMP cell", \
         datafile using (med(0, $1 + offset(0) - 0.14)):(med(0, $4)):(0.28):(0) with vectors nohead lw 4 lc rgb "#7f0000" title "MPM median", \
         datafile using (med(1, $1 + offset(1) - 0.14)):(med(1, $4)):(0.28):(0) with vectors nohead lw 4 lc rgb "#08306b" title "GIMP median", \
         1/0 with filledcurves lc rgb "#dcefdc" title "within a factor 3 of the paper"
    unset output
}
