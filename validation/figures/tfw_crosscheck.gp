set terminal pngcairo size 1000,420
set output 'validation/results/../figures/tfw_crosscheck.png'
set multiplot layout 1,2
set logscale x
set xrange [300:20000]
set xlabel 'StVK vertices'
set key bottom right
set title 'stretched sheet'
set ylabel 'periods across the width'
set yrange [0:12]
plot 'validation/results/tfw_crosscheck.dat' index 0 u 1:2 w lp pt 7 t 'StVK', 7.745 w l t 'TFW, 522-vertex base', 5 w l dt 2 t 'paper 5'
set title 'twisted cylinder'
set ylabel 'waves at mid-height'
set yrange [0:60]
plot 'validation/results/tfw_crosscheck.dat' index 1 u 1:2 w lp pt 7 t 'StVK', 49 w l t 'TFW, 1320-vertex base', 46 w l dt 2 t 'paper 46'
unset multiplot
