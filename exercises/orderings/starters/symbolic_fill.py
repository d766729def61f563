def symbolic_fill(n, edges, order):
    """Number of fill edges created by eliminating the variables in `order`.

    n:     number of variables, 0 ... n-1 (n >= 1).
    edges: list of pairs [i, j], i != j, of variables whose matrix entry is nonzero; a pair may
           repeat or appear reversed.
    order: list of the n variables, each once; order[0] is eliminated first.

    Returns an int: the pairs of variables joined by an elimination that were not already
    joined (by an edge or by earlier fill).
    """
    raise NotImplementedError("TODO: eliminate the variables in order and count the new pairs")
