# fig1.gp -- Fig. 1: 1D bar, displacement, velocity and stress of every particle at the final time,
# computed (points, at their position x_p) against the exact solution (line, at the exact
# position X + u(X, t)).
#
# Reads : datafile (e.g. results/fig1_data.csv): CSV, optional leading '#' comment lines, one
#         header line `X,x,u,u_exact,v,v_exact,sigma,sigma_exact`, then one row per particle
#         (in particle order). An empty field means "missing" and that point is skipped.
# Writes: outbase.png (pngcairo, 1000x1100) and outbase.svg (svg, same layout).
# Variables (set with gnuplot -e "..."): datafile, outbase required; subtitle (second title line).
# Usage (from the repository root):
#   gnuplot -e "datafile='results/fig1_data.csv'; outbase='results/fig1'; subtitle='...'" experiments/fig1.gp
# All quantities are in the model's dimensionless units.

if (!exists("datafile") || !exists("outbase")) {
    print "fig1.gp: datafile and outbase must be set (gnuplot -e \"datafile='...'; outbase='...'\")"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""

set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders          # first non-comment line is the header, never data
set datafile missing ''             # empty field = missing: the point is skipped

# A long subtitle would be clipped at 1000 px: break it after "; " (or else after the last ", "
# within the first 95 characters).
# lastcomma(s): position of the last ", " in s (0 if none).
lastcomma(s) = (strstrt(s, ", ") == 0) ? 0 : strstrt(s, ", ") + lastcomma(s[strstrt(s, ", ")+1:])
wrapsub(s) = (strlen(s) <= 95) ? s : \
             (strstrt(s, "; ") > 0) ? s[1:strstrt(s, "; ")] . "\n" . s[strstrt(s, "; ")+2:] : \
             (lastcomma(s[1:95]) > 0) ? s[1:lastcomma(s[1:95])] . "\n" . s[lastcomma(s[1:95])+2:] : s

maintitle = "Fig. 1: 1D bar, displacement, velocity and stress at the final time (dimensionless model units)" \
            . ((strlen(subtitle) > 0) ? "\n" . wrapsub(subtitle) : "")

# Computed values are drawn first as open circles, the exact line on top so both stay visible.
# Columns: 2 = x (current position); value/exact pairs 3/4 (u), 5/6 (v), 7/8 (sigma).
ccomp  = "#1f77b4"
cexact = "#d62728"

# The PNG's text is in DejaVu Sans (fonts-dejavu-core; mpmstab plot lets gnuplot see no other
# font); the SVG only names its font, which the viewer resolves.
do for [ext in "png svg"] {
    if (ext eq "png") {
        face = "DejaVu Sans"
        set terminal pngcairo size 1000,1100 font "DejaVu Sans,11" noenhanced
    } else {
        face = "sans"
        set terminal svg size 1000,1100 dynamic font "sans,11" noenhanced background "white"
    }
    set output outbase . "." . ext

    set multiplot layout 3,1 title maintitle font face . ",12" \
        margins 0.11,0.95,0.06,0.90 spacing 0,0.075

    set grid xtics ytics lc rgb "#dddddd"
    # Keys sit in the band just above each panel, so they never cover data.
    set key at graph 1, graph 1.015 right bottom horizontal noopaque nobox samplen 3
    set autoscale
    set xrange [-0.05:1.05]                      # the bar is [0, 1]
    set offsets 0, 0, graph 0.05, graph 0.05    # keep extreme values off the frame
    unset xlabel

    set ylabel "displacement u"
    plot datafile using 2:3 with points pt 6 ps 0.6 lc rgb ccomp title "computed, particles u_p", \
         datafile using ($1+$4):4 with lines lw 1.5 lc rgb cexact title "exact solution u(X,t)"

    set ylabel "velocity v"
    plot datafile using 2:5 with points pt 6 ps 0.6 lc rgb ccomp title "computed, particles v_p", \
         datafile using ($1+$4):6 with lines lw 1.5 lc rgb cexact title "exact solution v(X,t)"

    set ylabel "stress sigma"
    set xlabel "x"
    plot datafile using 2:7 with points pt 6 ps 0.6 lc rgb ccomp title "computed, particles sigma_p", \
         datafile using ($1+$4):8 with lines lw 1.5 lc rgb cexact title "exact solution sigma(X,t)"

    unset multiplot
    unset output
}
