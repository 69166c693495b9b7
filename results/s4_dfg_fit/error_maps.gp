set key noenhanced  # exp_plot: titles are plain names
set multiplot layout 1,2
set xlabel 'gloss'
set ylabel 'n.v'
set cblabel 'error of F0*scale+bias, F0=0.04'
set palette defined (-1 'blue', 0 'white', 1 'red')
set cbrange [-0.115646:0.115646]
set size ratio 1
set xrange [0:1]
set yrange [0:1]
set title 'polynomial fit'
plot 'error_map_polynomial.dat' using 1:2:3 with image notitle
set title 'Lazarov form, GGX refit'
plot 'error_map_lazarov.dat' using 1:2:3 with image notitle
unset multiplot

