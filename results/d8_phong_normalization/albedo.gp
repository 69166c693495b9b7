set key noenhanced  # exp_plot: titles are plain names
set logscale x; set xlabel 'Phong exponent n'; set ylabel 'albedo (hemisphere integral)';set key bottom left; set grid; set yrange [0:1.1];plot for [c=2:9] 'albedo.dat' u 1:c w lp t sprintf('r at %s deg', word('0 15 30 45 60 75 85 90', c-1))
