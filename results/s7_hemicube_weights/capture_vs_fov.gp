set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'field of view of the single plane (degrees)'
set ylabel 'share of the hemisphere captured'
set key top left
set grid
set yrange [0:1]
set arrow from 126.8699,0 to 126.8699,1 nohead dt 2
set label 'half extent 2: 126.87 deg' at 126.8699,0.1 right offset -1,0
plot 'capture_vs_fov.csv' every ::1 using 1:3 with lines lw 2 title 'cosine-weighted (irradiance)', '' every ::1 using 1:2 with lines lw 2 title 'solid angle'

