# tradeoff.gp -- speed against accuracy: max error over time against the work of the run
# (particle-steps, particles x steps), one panel per E, log-log, one series per method,
# time-step policy and grid, each with its marker and legend entry; the Pareto front of each E
# drawn as a black line through its runs (full colour), every dominated run faint.
#
# Reads : datafile (results/tradeoff_data.csv): '#' lines, then the header
#         E,panel,series,method,policy,cells,grid,particle_steps,steps,error,pareto and one row per run
#         drawn (stable, with an error; the runs left out are counted in the subtitle). panel:
#         0.. per E; series: 0.. per (method, policy, cells); method 0 mpm, 1 gimp, 2 cpgimp,
#         3 bspline2, 4 bspline3, 5 cpdi, 6 gimp/apic, 7 gimp/xpic(2), 8 gimp/fmpm(2), 9 another;
#         policy 0 fixed, 1 cfl, 2 adaptive, 3 min, 4 spectral; grid: the rank of cells, 0 the coarsest;
#         pareto: 1 on the Pareto front of its E.
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional: the runs drawn and left out).

if (!exists("datafile") || !exists("outbase")) {
    print "tradeoff.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

# The panels and the series, read from the data: each series' method, policy, cells and grid.
stats datafile using "panel" nooutput
panels = int(STATS_max) + 1
stats datafile using "series" nooutput
nseries = int(STATS_max) + 1
array panel_E[panels]
do for [k = 1:panels] {
    stats datafile using (column("panel") == k - 1 ? column("E") : 1/0) nooutput
    panel_E[k] = STATS_min
}
array s_method[nseries]
array s_policy[nseries]
array s_cells[nseries]
array s_grid[nseries]
do for [s = 1:nseries] {
    stats datafile using (column("series") == s - 1 ? column("method") : 1/0) nooutput
    s_method[s] = int(STATS_min)
    stats datafile using (column("series") == s - 1 ? column("policy") : 1/0) nooutput
    s_policy[s] = int(STATS_min)
    stats datafile using (column("series") == s - 1 ? column("cells") : 1/0) nooutput
    s_cells[s] = int(STATS_min)
    stats datafile using (column("series") == s - 1 ? column("grid") : 1/0) nooutput
    s_grid[s] = int(STATS_min)
}
stats datafile using "cells" nooutput
coarsest = int(STATS_min)

# Colour by method: the paper's MPM and GIMP and cpGIMP in three shades by grid, the others one
# colour each (they run on the coarsest grid only); marker by policy, open for MPM.
array method_name[10] = ["MPM", "GIMP", "cpGIMP", "B-spline 2", "B-spline 3", "CPDI", \
                         "GIMP, APIC", "GIMP, XPIC(2)", "GIMP, FMPM(2)", "another"]
array other_colour[7] = ["#bcbd22", "#000000", "#393b79", "#843c39", "#637939", "#7b4173", \
                         "#aaaaaa"]
array policy_name[5] = ["fixed dt", "CFL C h/c", "adaptive s x eq. (108)", "min(CFL, s x eq. (108))", \
                        "s x spectral limit"]
array policy_pt[5] = [7, 5, 9, 13, 11]
array colour[9] = ["#d62728", "#ff7f0e", "#9467bd", "#1f77b4", "#17becf", "#2ca02c", \
                   "#8c564b", "#e377c2", "#7f7f7f"]
s_colour(s) = s_method[s] < 3 ? colour[3 * s_method[s] + (s_grid[s] > 2 ? 2 : s_grid[s]) + 1] \
                              : other_colour[s_method[s] - 2]
s_pt(s) = policy_pt[s_policy[s] + 1] - (s_method[s] == 0 ? 1 : 0)
s_title(s) = sprintf("%s, %s%s", method_name[s_method[s] + 1], policy_name[s_policy[s] + 1], \
                     s_cells[s] != coarsest ? sprintf(", %d cells", s_cells[s]) : "")
sel(k, s, x) = (column("panel") == k - 1 && column("series") == s - 1) ? x : 1/0
# On the front (f = 1) or dominated (f = 0).
self(k, s, f, x) = (column("pareto") == f) ? sel(k, s, x) : 1/0
front(k, x) = (column("panel") == k - 1 && column("pareto") == 1) ? x : 1/0
# A dominated run's colour: the series' colour, mostly transparent.
faint(c) = "#B0" . c[2:7]

height = 120 + 360 * panels
# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1600,height font "DejaVu Sans,10" noenhanced
    } else {
        set terminal svg size 1600,height dynamic font "sans,10" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot layout panels,1 title "Speed against accuracy: max error over time against particle-steps (log-log)" . (strlen(subtitle) > 0 ? "\n" . subtitle : "") \
        margins 0.06,0.52,0.06,0.92 spacing 0.08,0.07
    set logscale xy
    set format x "%.0e"
    set format y "%.0e"
    set grid xtics ytics lc rgb "#e0e0e0"
    set xlabel "work of the run: particle-steps (particles x steps)"
    do for [k = 1:panels] {
        set ylabel sprintf("E = %g: max error over time", panel_E[k])
        if (k == 1) {
            set key at screen 0.99, screen 0.90 right top vertical maxrows 60 samplen 1 spacing 1.2 \
                title sprintf("%d cells unless named; faint: dominated", coarsest)
        } else {
            unset key
        }
        plot keyentry with lines lw 1.5 lc rgb "black" title "Pareto front (no run both cheaper and more accurate)", \
             for [s = 1:nseries] keyentry with points pt s_pt(s) ps 1.3 lc rgb s_colour(s) \
                 title s_title(s), \
             datafile using (front(k, column("particle_steps"))):(front(k, column("error"))) \
                 smooth unique with lines lw 1.5 lc rgb "black" notitle, \
             for [s = 1:nseries] datafile using (self(k, s, 0, column("particle_steps"))):(self(k, s, 0, column("error"))) \
                 with points pt s_pt(s) ps 1.1 lc rgb faint(s_colour(s)) notitle, \
             for [s = 1:nseries] datafile using (self(k, s, 1, column("particle_steps"))):(self(k, s, 1, column("error"))) \
                 with points pt s_pt(s) ps 1.6 lw 1.5 lc rgb s_colour(s) notitle
    }
    unset multiplot
    unset output
}
