"""Building maps: the point solvers of each family, the sweep, its workers and Dask backend, tiles and sweep files."""
