# spectral_edge.gp -- the measured edge over the spectral limit against the amplitude A, one
# series per scheme, log x, with the limit itself (1).
#
# Reads : datafile (results/spectral_edge_data.csv): '#' lines, then the header
#         schemes,A,<scheme 1>,..,<scheme n>,<scheme 1> meaningless,..,<scheme n> meaningless
#         and one row per amplitude: n in the first column, then each scheme's edge over the
#         limit, then the same where the run at the edge is meaningless (drawn with a cross);
#         an empty field: no edge in the scan, or not meaningless.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "spectral_edge.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

stats datafile using 1 nooutput
n = int(STATS_max)
array colour[8] = ["#d62728", "#ff7f0e", "#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f"]
array marker[8] = [7, 9, 5, 11, 13, 15, 3, 1]

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1000,650 font "DejaVu Sans,11" noenhanced
    } else {
        set terminal svg size 1000,650 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext
    set title "The bounded edge over the spectral limit, against the amplitude" . (strlen(subtitle) > 0 ? "\n" . subtitle : "")
    set logscale x
    set format x "%.0e"
    set xlabel "amplitude A"
    set ylabel "measured edge / spectral limit"
    set yrange [0:1.3]
    set grid
    set key left bottom box opaque
    plot 1 with lines lw 2 dt 2 lc rgb "#444444" title "spectral limit", \
         for [i = 1:n] datafile using 2:(column(i + 2)) with linespoints \
             lw 2 pt marker[(i - 1) % 8 + 1] ps 1.4 lc rgb colour[(i - 1) % 8 + 1] \
             title columnhead(i + 2), \
         for [i = 1:n] datafile using 2:(column(n + i + 2)) with points pt 2 ps 2.5 \
             lc rgb "black" title (i == 1 ? "run at the edge meaningless" : "")
    unset output
}
