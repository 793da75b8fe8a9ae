# tradeoff.gp -- speed against accuracy: max error over time against wall time (left) and
# against the number of steps (right), one row per E, log-log, by method and time-step policy.
#
# Reads : datafile (results/tradeoff_data.csv): '#' lines, then the header
#         E,method,policy,steps,wall_seconds,error (method 0 mpm, 1 gimp; policy 0 fixed, 1 cfl,
#         2 adaptive, 3 min; error empty when the run failed or its error reached A).
# Writes: outbase.png and outbase.svg.
# Variables: datafile, outbase (required), subtitle (optional).

if (!exists("datafile") || !exists("outbase")) {
    print "tradeoff.gp: datafile and outbase must be set"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders
set datafile missing ''

array Es[3] = [4, 64, 1000]
array policy_name[4] = ["fixed dt", "CFL C h/c", "adaptive s x eq. (108)", "min(CFL, s x eq. (108))"]
array policy_pt[4] = [7, 5, 9, 13]
sel(E, m, p, x) = (abs($1 - E) < 1e-9 && $2 == m && $3 == p && $6 > 0) ? x : 1/0

do for [ext in "png svg"] {
    if (ext eq "png") {
        set terminal pngcairo size 1100,1200 font "sans,10" noenhanced
    } else {
        set terminal svg size 1100,1200 dynamic font "sans,10" noenhanced background "white"
    }
    set output outbase . "." . ext
    set multiplot layout 3,2 title "Speed against accuracy: max error over time against cost (log-log)" . (strlen(subtitle) > 0 ? "\n" . subtitle : "") \
        margins 0.07,0.74,0.06,0.92 spacing 0.08,0.07
    set logscale xy
    set format y "%.0e"
    set grid xtics ytics lc rgb "#e0e0e0"
    do for [row = 1:3] {
        E = Es[row]
        do for [col = 1:2] {
            xcol = (col == 1) ? 5 : 4
            set xlabel (col == 1 ? "wall time of the run (s)" : "time steps")
            set ylabel sprintf("E = %g: max error over time", E)
            if (col == 2 && row == 1) {
                set key at screen 0.99, screen 0.90 right top vertical samplen 2 spacing 1.2
            } else {
                unset key
            }
            plot for [m = 1:0:-1] for [p = 0:3] datafile using (sel(E, m, p, column(xcol))):(sel(E, m, p, $6)) \
                 with points pt (policy_pt[p + 1] - (m == 0 ? 1 : 0)) ps 1.3 \
                 lc rgb (m == 1 ? "#1f77b4" : "#d62728") \
                 title sprintf("%s, %s", (m == 1 ? "GIMP" : "MPM"), policy_name[p + 1])
        }
    }
    unset multiplot
    unset output
}
