set terminal pngcairo size 900,500
set output 'validation/results/../figures/stretch.png'
set xlabel 'y across the width [mm]'
set ylabel 'out-of-plane displacement [mm]'
set title 'Stretch test, x = L/2'
plot 'validation/results/stretch_profile_0.dat' w l t '2.5 mm (2.50 mm, 4141 vertices)', 'validation/results/stretch_profile_1.dat' w l t 'r_opt (4.17 mm, 1525 vertices)', 'validation/results/stretch_profile_2.dat' w l t '2 r_opt (8.33 mm, 403 vertices)', 'validation/results/stretch_profile_3.dat' w l t '5 mm (5.00 mm, 1071 vertices)'
