# fig2.gp -- Fig. 2: 1D bar (GIMP), per-step error, eq. (108) time-step bound and grid crossings.
# Reads : datafile (e.g. results/fig2_data.csv), header `step,time,error,dt_stable,crossings`,
#         optional leading '#' comment lines; empty fields are treated as not measured.
# Writes: outbase.png and outbase.svg.
# Usage (from the repository root):
#   gnuplot -e "datafile='results/fig2_data.csv'; outbase='results/fig2'; subtitle='...'; dt=1e-5" experiments/fig2.gp
# The plotting logic is shared with fig3.gp and lives in history.gp next to this file.
figtitle = "Fig. 2: 1D bar, error, eq. (108) bound and grid crossings, GIMP"
# Directory of this script (ARG0 is the script path), so the shared file is found from any cwd.
scriptdir = ""
do for [i = strlen(ARG0):1:-1] { if (scriptdir eq "" && ARG0[i:i] eq "/") { scriptdir = ARG0[1:i] } }
load scriptdir . "history.gp"
