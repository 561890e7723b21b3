set terminal pngcairo size 900,450
set output 'validation/results/../figures/tfw_sheared_rectangle_stvk_loop.png'
set xlabel 'x along the mid-line [mm]'
set ylabel 'z [mm]'
set title 'StVK + Loop element, sheared rectangle, y = 64 mm'
set key below
plot 'validation/results/tfw_sheared_rectangle_stvk_loop_probe.dat' w l t 'StVK + Loop element'
