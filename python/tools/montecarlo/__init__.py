"""Monte Carlo: one scenario over many seeds, locally or on a Dask cluster (`auv-montecarlo`)."""
