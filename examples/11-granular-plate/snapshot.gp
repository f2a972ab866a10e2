# The plate's vertical displacement at t = 100 us of the 1 m/s run (csv_1/snapshot_2.csv: the second
# of six snapshots), when the front has crossed it, less its mean: the absorbing (dashpot) edges hold
# no static load, so the whole plate also moves down. Re-run with: gnuplot snapshot.gp
set terminal pngcairo size 900,420 enhanced font 'Sans,11'
set output 'snapshot.png'
set datafile separator ','
set title 'Plate displacement u_y less its mean, t = 100 μs (1 m/s strike)'
set xlabel 'x (mm)'
set ylabel 'y (mm)'
set cblabel 'u_y - mean (nm)'
stats 'csv_1/snapshot_2.csv' using 4 nooutput
mean = STATS_mean
set view map
set palette defined (-1 'blue', 0 'white', 1 'red')
splot 'csv_1/snapshot_2.csv' using ($1*1e3):($2*1e3):(($4 - mean)*1e9) with pm3d notitle
