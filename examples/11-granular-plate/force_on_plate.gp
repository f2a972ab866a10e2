# The total normal force the beads exert on the plate against time, for strikes at 0.1, 0.3 and 1 m/s
# (two decades of shock energy). Re-run with: gnuplot force_on_plate.gp
set terminal pngcairo size 900,560 enhanced font 'Sans,11'
set output 'force_on_plate.png'
set datafile separator ','
set title 'Force on the plate'
set xlabel 'time (μs)'
set ylabel 'normal force (N)'
set logscale y
set yrange [1e-2:*]
set key top right
plot 'csv_0.1/energies.csv' using ($1*1e6):($11 > 0 ? $11 : 1/0) with lines lw 2 title '0.1 m/s', \
     'csv_0.3/energies.csv' using ($1*1e6):($11 > 0 ? $11 : 1/0) with lines lw 2 title '0.3 m/s', \
     'csv_1/energies.csv' using ($1*1e6):($11 > 0 ? $11 : 1/0) with lines lw 2 title '1 m/s'
