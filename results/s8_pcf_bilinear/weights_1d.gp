set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'sub-texel offset f'
set ylabel 'weight (of 1)'
set key outside
set grid
plot 'weights_1d.csv' every ::1 using 1:2 with lines lw 2 title 'box: outer texel (1-f)/3', '' every ::1 using 1:3 with lines lw 2 title 'box: inner texel 1/3', '' every ::1 using 1:4 with lines lw 2 dt 2 title 'fast: outer texel', '' every ::1 using 1:5 with lines lw 2 dt 2 title 'fast: inner texel'

