"""Log tools (`auv-lcmlog`): summary, csv, npz, annotations, state timelines, MCAP for Foxglove."""
