# Writes the Rhine polyline of the R package mapdata's `rivers` database as lon,lat CSV.
#   Rscript rhine.R LIBS OUT.csv
# LIBS: library folders (separated by ':') holding the R packages maps and mapdata, searched
# before R's own; build.sh passes those of Debian's r-cran-maps and r-cran-mapdata, installed or
# unpacked from `apt-get download`.
# The `rivers` database has no names: the Rhine is its polyline number 36 (162 points, from
# 8.650 E 46.633 N, Lake Toma at the source of the Vorderrhein, to 4.800 E 51.800 N, the Merwede
# near Dordrecht). The script checks both ends so that a different database fails loudly.
args <- commandArgs(trailingOnly = TRUE)
.libPaths(c(strsplit(args[1], ":", fixed = TRUE)[[1]], .libPaths()))
suppressPackageStartupMessages({
  library(maps)
  library(mapdata)
})
r <- map("rivers", plot = FALSE)
breaks <- c(0, which(is.na(r$x)), length(r$x) + 1)
i <- 36
idx <- (breaks[i] + 1):(breaks[i + 1] - 1)
lon <- r$x[idx]
lat <- r$y[idx]
stopifnot(length(idx) == 162,
          abs(lon[1] - 8.650) < 0.01, abs(lat[1] - 46.633) < 0.01,
          abs(lon[162] - 4.800) < 0.01, abs(lat[162] - 51.800) < 0.01)
write.csv(data.frame(lon = sprintf("%.6f", lon), lat = sprintf("%.6f", lat)), args[2],
          row.names = FALSE, quote = FALSE)
