set terminal pngcairo size 900,450
set output 'validation/results/../figures/tfw_sheared_rectangle.png'
set xlabel 'x along the mid-line [mm]'
set ylabel 'z of the wrinkled surface [mm]'
set title 'TFW sheared rectangle (990-vertex base, 3 mm shear), y = 64 mm'
set key below
plot 'validation/results/tfw_sheared_rectangle_probe.dat' w l t 'TFW, Loop level 3'
