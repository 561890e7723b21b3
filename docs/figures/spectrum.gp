# gnuplot script for docs/spectrum.md (run in docs/figures after spectrum_fig; see spectrum_fig.c)
if (!exists("out")) out = "spectrum.svg"
if (out[strlen(out)-2:] eq "svg") set terminal svg size 900,640 font "sans,12"; else set terminal pngcairo size 900,640
set output out
set multiplot layout 2,1
set title "probe across the wrinkles (rest-domain segment, 400 samples)"
set xlabel "s [mm]"; set ylabel "z [mm]"
plot "spectrum_probe.dat" using ($1*1e3):($2*1e3) with lines lw 1.5 title "sampled out-of-plane displacement"
set title "power spectrum (quadratic detrend, Hann window, 4x zero padding)"
set xlabel "wavenumber [1/m]"; set ylabel "|X_k|^2 / peak"; set logscale y; set format y "10^{%L}"; set xrange [0:400]; set yrange [1e-7:2]
set arrow 1 from 1/0.0123, graph 0 to 1/0.0123, graph 1 nohead dt 2 lc rgb "black"
set label 1 "true 1/lambda" at 1/0.0123, graph 0.92 offset 1,0
plot "spectrum_power.dat" using 1:2 with linespoints pt 7 ps 0.3 title "spectrum"
unset multiplot
