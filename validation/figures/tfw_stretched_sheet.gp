set terminal pngcairo size 900,450
set output 'validation/results/../figures/tfw_stretched_sheet.png'
set xlabel 'y across the width [mm]'
set ylabel 'z of the wrinkled surface [mm]'
set title 'TFW stretched sheet (522-vertex base, 12.78%), x = L/2'
set key below
plot 'validation/results/tfw_stretched_sheet_probe.dat' w l t 'TFW, Loop level 3'
