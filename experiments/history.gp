# history.gp -- shared plotting logic for Fig. 2 and Fig. 3 (per-step history of a 1D bar run).
# Not meant to be run directly: experiments/fig2.gp and experiments/fig3.gp set `figtitle`
# and then `load` this file.
#
# Reads : datafile  CSV, optional leading '#' comment lines, one header line
#                   `step,time,error,dt_stable,crossings`, then one row per recorded step.
#                   An empty field means "not measured" and is skipped. On the log-scale
#                   panels, values that are not finite and > 0 (0, negative, inf, nan) are skipped
#                   too; the remaining points are joined by a line.
# Writes: outbase.png (pngcairo, 1000x1100) and outbase.svg (svg, same layout).
# Variables (set with gnuplot -e "..."):
#   datafile, outbase  required
#   subtitle           second title line (optional, normally given)
#   dt                 the run's fixed time step; drawn as the dashed "dt used" line (optional)
#   figtitle           first title line, set by the wrapper script
#
# Panels, all against the step number (column 1):
#   top    column 3, max over particles of |u_p - u(X_p,t)|, log y
#   middle column 4, eq. (108) stable time-step bound, log y, plus dashed line at dt
#   bottom column 5, cumulative grid crossings, linear y

if (!exists("datafile") || !exists("outbase")) {
    print "history.gp: datafile and outbase must be set (gnuplot -e \"datafile='...'; outbase='...'\")"
    exit error "missing variables"
}
if (!exists("subtitle")) subtitle = ""
if (!exists("figtitle")) figtitle = "1D bar history"
if (!exists("dt")) dt = NaN

# Keep only finite, strictly positive values (for log axes); anything else becomes NaN.
pos(x) = (x > 0 && x < 1e300) ? x : NaN
fin(x) = (abs(x) < 1e300) ? x : NaN
isnum(x) = (x == x) ? 1 : 0
# Multiplicative padding for a log axis spanning [lo:hi]: 8% of the span in decades, at least x1.5.
logpad(lo, hi) = ((hi/lo)**0.08 > 1.5) ? (hi/lo)**0.08 : 1.5
# Full-precision text for the intermediate tables.
num(x) = sprintf("%.17g", x)

# ---- read the CSV once, keeping only the usable points of each series -------------------
set datafile separator comma
set datafile commentschars '#'
set datafile columnheaders          # first non-comment line is the header, never data
set datafile missing ''             # empty field = not measured: the row is skipped

stats datafile using 1 name "S" nooutput
if (!exists("S_records") || S_records < 1) {
    print sprintf("history.gp: no data rows in %s", datafile)
    exit error "no data"
}
nrows = S_records
xlo = S_min
xhi = S_max
if (xhi <= xlo) { xlo = xlo - 1; xhi = xhi + 1 }

# Count the usable values first (column(N) keeps rows with an empty field in the count, so
# stats never sees an all-missing column), then copy them into tables.
stats datafile using (isnum(pos(column(3)))) name "NE" nooutput
stats datafile using (isnum(pos(column(4)))) name "NB" nooutput
stats datafile using (isnum(fin(column(5)))) name "NC" nooutput
nerr = int(NE_sum)
nbound = int(NB_sum)
ncross = int(NC_sum)

$ERR << EOD
EOD
$BND << EOD
EOD
$CRS << EOD
EOD
if (nerr > 0) {
    set table $ERR
    plot datafile using (num($1)):(num($3)) with table if (isnum(pos($3)))
}
if (nbound > 0) {
    set table $BND
    plot datafile using (num($1)):(num($4)) with table if (isnum(pos($4)))
}
if (ncross > 0) {
    set table $CRS
    plot datafile using (num($1)):(num($5)) with table if (isnum(fin($5)))
}
unset table

# From here on only the tables above are plotted (tab/space separated, no header).
set datafile separator whitespace
set datafile nocolumnheaders

havedt = isnum(pos(dt))

if (nerr > 0) {
    stats $ERR using 2 name "E" nooutput
    elo = E_min
    ehi = E_max
}
blo = dt
bhi = dt
if (nbound > 0) {
    stats $BND using 2 name "B" nooutput
    blo = havedt ? ((dt < B_min) ? dt : B_min) : B_min
    bhi = havedt ? ((dt > B_max) ? dt : B_max) : B_max
}
if (ncross > 0) {
    stats $CRS using 2 name "C" nooutput
    clo = C_min
    chi = C_max
}

# Few points: draw markers as well as lines, so a 10-row run is still readable.
style(n) = (n <= 200) ? "linespoints pt 7 ps 0.7" : "lines"
styE = style(nerr)
styB = style(nbound)
styC = style(ncross)

# A log axis spanning fewer than ~2.5 decades gets few labels; add labelled 2x and 5x tics.
# Under one decade, 3x tics are added as well. Usage: set TLO and THI (the axis limits), then
# `eval tics125`.
tics125 = "do for [k = floor(log10(TLO)) : ceil(log10(THI))] { set ytics add (2*10.0**k, 5*10.0**k); if (THI/TLO < 10) { set ytics add (3*10.0**k) } }"

# A long subtitle would be clipped at 1000 px: break it after "; " (or else after the last ", "
# within the first 95 characters).
# lastcomma(s): position of the last ", " in s (0 if none).
lastcomma(s) = (strstrt(s, ", ") == 0) ? 0 : strstrt(s, ", ") + lastcomma(s[strstrt(s, ", ")+1:])
wrapsub(s) = (strlen(s) <= 95) ? s : \
             (strstrt(s, "; ") > 0) ? s[1:strstrt(s, "; ")] . "\n" . s[strstrt(s, "; ")+2:] : \
             (lastcomma(s[1:95]) > 0) ? s[1:lastcomma(s[1:95])] . "\n" . s[lastcomma(s[1:95])+2:] : s

maintitle = figtitle . ((strlen(subtitle) > 0) ? "\n" . wrapsub(subtitle) : "")

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

    set xrange [xlo:xhi]
    set grid xtics ytics lc rgb "#dddddd"
    # Keys sit in the band just above each panel, so they never cover data.
    set key at graph 1, graph 1.015 right bottom horizontal noopaque nobox samplen 3

    # ---- (top) max error in u over the particles -------------------------------------------
    unset label
    unset xlabel
    set logscale y
    set format y "%.0e"
    set ytics autofreq
    set ylabel "max |u_p - u(X_p,t)|"
    if (nerr > 0) {
        TLO = elo/logpad(elo,ehi)
        THI = ehi*logpad(elo,ehi)
        set yrange [TLO:THI]
        if (THI/TLO < 10**2.5) { eval tics125 }
        plot $ERR using 1:2 with @styE lw 1.5 lc rgb "#1f77b4" \
             title "max over particles of |u_p - u(X_p,t)|"
    } else {
        set yrange [0.1:1]
        set label 1 "no positive error values in the data" at graph 0.5,0.5 center
        plot NaN notitle
    }

    # ---- (middle) eq. (108) stable time-step bound and the step actually used ---------------
    unset label
    set ytics autofreq
    set ylabel "time step"
    if (nbound > 0 || havedt) {
        TLO = blo/logpad(blo,bhi)
        THI = bhi*logpad(blo,bhi)
        set yrange [TLO:THI]
        if (THI/TLO < 10**2.5) { eval tics125 }
        if (nbound == 0) {
            set label 1 "no positive dt_stable values in the data" at graph 0.5,0.25 center
        }
        if (nbound > 0 && havedt) {
            plot $BND using 1:2 with @styB lw 1.5 lc rgb "#d62728" title "dt_stable, eq. (108) bound", \
                 dt with lines dashtype 2 lw 2 lc rgb "black" title sprintf("dt used = %g", dt)
        }
        if (nbound > 0 && !havedt) {
            plot $BND using 1:2 with @styB lw 1.5 lc rgb "#d62728" title "dt_stable, eq. (108) bound", \
                 keyentry with lines dashtype 2 lw 2 lc rgb "black" title "dt used: not given"
        }
        if (nbound == 0) {
            plot dt with lines dashtype 2 lw 2 lc rgb "black" title sprintf("dt used = %g", dt)
        }
    } else {
        set yrange [0.1:1]
        set label 1 "no positive dt_stable values in the data and no dt given" at graph 0.5,0.5 center
        plot NaN notitle
    }

    # ---- (bottom) cumulative grid crossings ------------------------------------------------
    unset label
    unset logscale y
    set format y "%h"
    set ytics autofreq
    set ylabel "cumulative grid crossings"
    set xlabel "time step number"
    if (ncross > 0) {
        if (chi > clo) { set yrange [clo-0.05*(chi-clo):chi+0.05*(chi-clo)] } else { set yrange [clo-1:chi+1] }
        plot $CRS using 1:2 with @styC lw 1.5 lc rgb "#2ca02c" \
             title "particle grid-cell crossings (cumulative)"
    } else {
        set yrange [0:1]
        set label 1 "no crossing counts in the data" at graph 0.5,0.5 center
        plot NaN notitle
    }

    unset multiplot
    unset output
}
