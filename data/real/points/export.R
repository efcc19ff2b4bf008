# Exports the spatstat.data point patterns of this corpus as CSV files.
# Usage: Rscript export.R OUTDIR WINDOWS_TSV
# Needs: Debian packages r-base-core, r-cran-spatstat.data, r-cran-spatstat.geom.
# Every pattern is translated so that its observation window's lower corner is the origin.
suppressMessages({
  library(spatstat.data)
  library(spatstat.geom)
})

args <- commandArgs(trailingOnly = TRUE)
stopifnot(length(args) == 2)
out <- args[1]
windows_tsv <- args[2]

# A real number as text: 15 significant digits (R's as.character), rounding error of the
# translation removed, always with a decimal point ("6" -> "6.0").
num <- function(v) {
  stopifnot(all(is.finite(v)))
  s <- as.character(round(v, 10))
  s[s == "-0"] <- "0"
  stopifnot(!any(grepl("e", s, fixed = TRUE)))
  ifelse(grepl(".", s, fixed = TRUE), s, paste0(s, ".0"))
}
# A categorical mark as an integer label 0..k-1, in the order of the factor's levels.
lab <- function(f) as.character(as.integer(f) - 1L)

window_lines <- character(0)

write_case <- function(name, cols, window, labels = NULL) {
  # cols: named list of already formatted character vectors, in column order.
  df <- as.data.frame(cols, stringsAsFactors = FALSE, optional = TRUE)
  names(df) <- names(cols)
  con <- file(file.path(out, paste0(name, ".csv")), open = "wb")
  writeLines(paste(names(df), collapse = ","), con, sep = "\n")
  writeLines(do.call(paste, c(unname(as.list(df)), sep = ",")), con, sep = "\n")
  close(con)
  window_lines <<- c(window_lines, paste(c(name, num(window)), collapse = "\t"))
  if (!is.null(labels)) {
    cat(sprintf("%s: label %d = %s\n", name, seq_along(labels) - 1L, labels), sep = "")
  }
}

# A planar pattern restricted to the rectangle [x0, x0+w] x [y0, y0+h] and moved to the origin.
planar <- function(X, x0, y0, w, h) {
  X <- X[owin(c(x0, x0 + w), c(y0, y0 + h))]
  list(X = X, x = num(X$x - x0), y = num(X$y - y0), window = c(w, h))
}
whole <- function(X) {
  W <- Window(X)
  stopifnot(W$type == "rectangle")
  planar(X, W$xrange[1], W$yrange[1], diff(W$xrange), diff(W$yrange))
}

data(longleaf, amacrine, anemones, bei, lansing, spruces, swedishpines, redwood,
     japanesepines, osteo, finpines)

# longleaf: 584 pines in 200 x 200 m, mark = diameter at breast height (cm).
p <- whole(longleaf)
write_case("longleaf", list(x = p$x, y = p$y, dbh = num(marks(p$X))), p$window)

# amacrine: 294 cells in a 1.601 x 1 frame (unit 662 microns), type off/on.
p <- whole(amacrine)
write_case("amacrine", list(x = p$x, y = p$y, label = lab(marks(p$X))), p$window,
           levels(marks(amacrine)))

# anemones: 231 beadlet anemones in 280 x 180 units, mark = diameter (same units).
p <- whole(anemones)
write_case("anemones", list(x = p$x, y = p$y, diameter = num(marks(p$X))), p$window)

# bei_subset: the 250 x 250 m square [0, 250] x [50, 300] of the Barro Colorado plot, where the
# density of Beilschmiedia trees falls steadily with x (215, 138, 126, 104 and 17 trees in the
# five 50 m strips from left to right).
p <- planar(bei, 0, 50, 250, 250)
write_case("bei_subset", list(x = p$x, y = p$y), p$window)

# lansing_subset: the square [0, 0.5] x [0, 0.5] (462 x 462 ft) of Lansing Woods, species as
# label 0..5 (levels in alphabetical order). Points at the location of an earlier point would be
# dropped (lansing has one such pair, outside this square).
p <- planar(lansing[!duplicated(unmark(lansing))], 0, 0, 0.5, 0.5)
write_case("lansing_subset", list(x = p$x, y = p$y, label = lab(marks(p$X))), p$window,
           levels(marks(lansing)))

# spruces: 134 Norwegian spruces in 56 x 38 m, mark = diameter (m).
p <- whole(spruces)
write_case("spruces", list(x = p$x, y = p$y, diameter = num(marks(p$X))), p$window)

# swedishpines: 71 saplings in 96 x 100 dm (regular, inhibited).
p <- whole(swedishpines)
write_case("swedishpines", list(x = p$x, y = p$y), p$window)

# redwood: 62 seedlings, window [0,1] x [-1,0] moved to [0,1] x [0,1] (clustered).
p <- whole(redwood)
write_case("redwood", list(x = p$x, y = p$y), p$window)

# finpines: 126 Scots pines in 10 x 10 m (clustered: the data set a Matern cluster process is
# classically fitted to), marks diameter at breast height (cm) and height (m).
p <- whole(finpines)
write_case("finpines", list(x = p$x, y = p$y, diameter = num(marks(p$X)$diameter),
                            height = num(marks(p$X)$height)), p$window)

# japanesepines: 65 pines in the unit square (unit 5.7 m), close to complete randomness.
p <- whole(japanesepines)
write_case("japanesepines", list(x = p$x, y = p$y), p$window)

# osteo_brick: the brick with the most points (row 36: bone c77za9, brick 6, 81 x 100 x 100
# microns, 29 points). Points outside the brick's box (one, at x = 81.8) are dropped; z
# (depth, -100..0) is moved to 0..100.
X <- osteo$pts[[36]]
b <- as.box3(X)
cxyz <- coords(X)
inside <- cxyz$x >= b$xrange[1] & cxyz$x <= b$xrange[2] &
  cxyz$y >= b$yrange[1] & cxyz$y <= b$yrange[2] &
  cxyz$z >= b$zrange[1] & cxyz$z <= b$zrange[2]
cxyz <- cxyz[inside, ]
write_case("osteo_brick",
           list(x = num(cxyz$x - b$xrange[1]), y = num(cxyz$y - b$yrange[1]),
                z = num(cxyz$z - b$zrange[1])),
           c(diff(b$xrange), diff(b$yrange), diff(b$zrange)))

writeLines(window_lines, windows_tsv)
