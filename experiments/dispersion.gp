# dispersion.gp -- the phase speed c_num / c of each scheme's physical branch against kh (the
# phase of the wave per cell, 2 pi / kh cells per wavelength), one panel per Courant number, one
# curve per scheme; the exact speed (1) and the band of a 1% phase error as references. A scheme
# at or above its spectral limit at a panel's Courant number has no curve there, and a curve ends
# where the branch stops propagating.
#
# Reads : datafile (results/dispersion_data.csv): '#' lines, then the header
#         panel,courant,series,scheme,kh,phase_speed,damping. panel: 0.. per Courant number;
#         series: 0.. per scheme (its name in the scheme column).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "dispersion.gp: datafile and outbase must be set"
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
array panel_C[panels]
do for [k = 1:panels] {
    stats datafile using (column("panel") == k - 1 ? column("courant") : 1/0) nooutput
    panel_C[k] = STATS_min
}
array names[nseries]
do for [s = 1:nseries] {
    names[s] = ""
}
# The name of each series, from the scheme column (strings are read row by row).
do for [s = 1:nseries] {
    stats datafile using (column("series") == s - 1 ? (names[s] = strcol("scheme"), 0) : 1/0) nooutput
}
stats datafile using "phase_speed" nooutput
y_low = STATS_min > 0.5 ? 0.5 : 0.0
y_high = STATS_max > 1.1 ? ceil(STATS_max * 10.0) / 10.0 : 1.1

# Every basis with FLIP in solid lines, the other transfers dashed (a series named "a = b" is
# several schemes whose curves coincide).
array colour[12] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", \
                    "#17becf", "#e377c2", "#7f7f7f", "#bcbd22", "#000000", "#aec7e8"]
dash(s) = strstrt(names[s], "/") > 0 ? 2 : 1

set xrange [0:pi]
set yrange [y_low:y_high]
set xtics ("0" 0, "pi/4" pi/4, "pi/2" pi/2, "3pi/4" 3*pi/4, "pi" pi)
set x2tics ("16" 2*pi/16, "8" 2*pi/8, "4" 2*pi/4, "3" 2*pi/3, "2" pi)
set x2range [0:pi]
set grid
set xlabel "kh (radians per cell)"
set x2label "cells per wavelength"
set ylabel "phase speed c_num / c"

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [format in "png svg"] {
    if (format eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 1600,1000 font "DejaVu Sans,10" noenhanced
    } else {
        face = "Arial"
        set terminal svg size 1600,1000 font "Arial,10" noenhanced background "white"
    }
    set output outbase . "." . format
    set multiplot layout 2, 2 title "Phase speed of the physical branch against kh, one panel per Courant number" . (strlen(subtitle) > 0 ? "\n" . subtitle : "") \
        margins 0.05, 0.79, 0.07, 0.88 spacing 0.07, 0.12
    do for [k = 1:panels] {
        set title sprintf("C = c dt / h = %g", panel_C[k])
        if (k == 1) { set key at screen 0.995, screen 0.80 right top font face . ",10" box opaque } else { unset key }
        plot 1 with lines lw 1 lc rgb "#444444" dt 3 title "exact", \
             0.99 with lines lw 1 lc rgb "#999999" dt 2 title "1% phase error", \
             1.01 with lines lw 1 lc rgb "#999999" dt 2 notitle, \
             for [s = 1:nseries] datafile \
                 using (column("panel") == k - 1 && column("series") == s - 1 ? column("kh") : 1/0):"phase_speed" \
                 with lines lw 2 dt dash(s) lc rgb colour[(s - 1) % 12 + 1] title names[s]
    }
    unset multiplot
    set output
}
