def read_edges(text):
    """The EDGE_SE2 records of a 2-D g2o file, in file order.

    text: the whole file as one string. Edge lines read
        EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33
    (the upper triangle of the information matrix, row by row); other lines are skipped.
    Returns an m x 14 array (or list of lists): i, j, dx, dy, dtheta, then the full
    symmetric 3x3 information matrix row by row.
    """
    raise NotImplementedError("split each line; keep EDGE_SE2 lines; rebuild the full matrix")
