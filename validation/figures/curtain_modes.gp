set terminal pngcairo size 1000,520
set output 'validation/results/../figures/curtain_modes.png'
set grid
set key top right
set xlabel 'depth below the gathered top edge [mm]'
set ylabel 'modal amplitude [mm]'
set xrange [0:80]
plot 'validation/results/curtain_0.dat' u 1:4 w l lw 2 lc 1 t 'lambda0 mode, B = 1e-06, rho_A = 0.15', 'validation/results/curtain_0.dat' u 1:5 w l lw 2 dt 2 lc 1 t '2 lambda0 mode (max: 31.5 mm; L_w tension 34.3 / compression 30.0 mm)', 'validation/results/curtain_1.dat' u 1:4 w l lw 2 lc 2 t 'lambda0 mode, B = 2e-06, rho_A = 0.15', 'validation/results/curtain_1.dat' u 1:5 w l lw 2 dt 2 lc 2 t '2 lambda0 mode (max: nan mm; L_w tension 24.3 / compression 26.7 mm)', 'validation/results/curtain_2.dat' u 1:4 w l lw 2 lc 3 t 'lambda0 mode, B = 4e-06, rho_A = 0.15', 'validation/results/curtain_2.dat' u 1:5 w l lw 2 dt 2 lc 3 t '2 lambda0 mode (max: 66.4 mm; L_w tension 17.2 / compression 23.8 mm)', 'validation/results/curtain_3.dat' u 1:4 w l lw 2 lc 4 t 'lambda0 mode, B = 2e-06, rho_A = 0.60', 'validation/results/curtain_3.dat' u 1:5 w l lw 2 dt 2 lc 4 t '2 lambda0 mode (max: nan mm; L_w tension 48.5 / compression 26.7 mm)', 'validation/results/curtain_4.dat' u 1:4 w l lw 2 lc 5 t 'lambda0 mode, B = 2e-06, rho_A = 2.50', 'validation/results/curtain_4.dat' u 1:5 w l lw 2 dt 2 lc 5 t '2 lambda0 mode (max: 27.4 mm; L_w tension 156.6 / compression 26.7 mm)'
