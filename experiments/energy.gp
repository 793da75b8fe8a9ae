# energy.gp -- the energy balance error over time, one panel per Table 1 cell (two rows of panels
# where there are more than two), one series per transfer and update order.
#
# Reads : datafile (results/energy_data.csv): '#' lines, then the header
#         panel,series,cell,method,t,energy_balance and one row per drawn step. panel: 0.. per
#         cell; series: 0.. per transfer and update order (alphabetical); energy_balance: the
#         balance error per the initial energy.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "energy.gp: datafile and outbase must be set"
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
rows = panels > 2 ? 2 : 1
cols = int((panels + rows - 1) / rows)
array cells[panels]
array names[nseries]
do for [k = 1:panels] {
    cells[k] = ""
    stats datafile using (column("panel") == k - 1 ? (cells[k] = strcol("cell"), 0) : 1/0) nooutput
}
do for [s = 1:nseries] {
    names[s] = ""
    stats datafile using (column("series") == s - 1 ? (names[s] = strcol("method"), 0) : 1/0) nooutput
}

set xlabel "t"
set ylabel "energy balance error / initial energy"
set grid
# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [format in "png svg"] {
    if (format eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 1500,550 * rows font "DejaVu Sans,10" noenhanced
    } else {
        face = "Arial"
        set terminal svg size 1500,550 * rows font "Arial,10" noenhanced background "white"
    }
    set key outside right top font face . ",9"
    set output outbase . "." . format
    set multiplot layout rows, cols title "Energy balance over time, each transfer and update order (" . subtitle . ")"
    do for [k = 1:panels] {
        set title cells[k]
        plot for [s = 1:nseries] datafile \
            using (column("panel") == k - 1 && column("series") == s - 1 ? column("t") : 1/0):"energy_balance" \
            with lines lw 1.5 title names[s]
    }
    unset multiplot
    unset output
}
