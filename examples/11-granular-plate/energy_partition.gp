# The energy partition against time, as fractions of the input, for the strike at 1 m/s
# (csv_1/energies.csv from `sedwave interface --csv`). Re-run with: gnuplot energy_partition.gp
set terminal pngcairo size 900,560 enhanced font 'Sans,11'
set output 'energy_partition.png'
set datafile separator ','
set title 'Energy partition, strike at 1 m/s (fractions of the input)'
set xlabel 'time (μs)'
set ylabel 'fraction of the input energy'
set key outside right
set yrange [0:1.05]
input = real(system("sed -n 's/.*input energy \\([0-9.e+-]*\\) J.*/\\1/p' csv_1/energies.csv"))
plot 'csv_1/energies.csv' using ($1*1e6):(($2+$3)/input) with lines lw 2 title 'grains, kinetic', \
     '' using ($1*1e6):($4/input) with lines lw 2 title 'contacts', \
     '' using ($1*1e6):(($5+$6)/input) with lines lw 2 title 'plate', \
     '' using ($1*1e6):($7/input) with lines lw 2 title 'friction (dissipated)', \
     '' using ($1*1e6):($9/input) with lines lw 2 title 'absorbed at the plate''s sides'
