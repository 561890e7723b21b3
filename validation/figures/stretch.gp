set terminal pngcairo size 1200,500 noenhanced
set output 'validation/results/../figures/stretch.png'
set key outside right top
set xlabel 'y across the width [mm]'
set ylabel 'out-of-plane displacement [mm]'
set title 'Stretch test, x = L/2 (solid: union-jack grid, dashed: Delaunay)'
plot 'validation/results/stretch_profile_0.dat' w l t 'grid 2.5 mm (2.50 mm, 4141 vertices)', 'validation/results/stretch_profile_1.dat' w l t 'grid r_opt (4.17 mm, 1525 vertices)', 'validation/results/stretch_profile_2.dat' w l t 'grid 2 r_opt (8.33 mm, 403 vertices, flat)', 'validation/results/stretch_profile_3.dat' w l t 'grid 5 mm (5.00 mm, 1071 vertices)', 'validation/results/stretch_profile_del0.dat' w l dt 2 t 'Delaunay 2.5 mm (2.50 mm, 5102 vertices, flat)', 'validation/results/stretch_profile_del1.dat' w l dt 2 t 'Delaunay r_opt (4.17 mm, 1881 vertices, flat)', 'validation/results/stretch_profile_del2.dat' w l dt 2 t 'Delaunay 2 r_opt (8.33 mm, 478 vertices, flat)', 'validation/results/stretch_profile_del3.dat' w l dt 2 t 'Delaunay 5 mm (5.00 mm, 1309 vertices, flat)'
