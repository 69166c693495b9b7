set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'view-space z of the normal'
set ylabel 'mean angular error (deg)'
set logscale y
set grid
set key top right
plot 'mittring_by_z.csv' skip 1 using (($1+$2)/2):3 with linespoints title 'Mittring 8:8', '' skip 1 using (($1+$2)/2):5 with linespoints title 'Mittring 12:12', '' skip 1 using (($1+$2)/2):7 with linespoints title 'octahedral 12:12'
