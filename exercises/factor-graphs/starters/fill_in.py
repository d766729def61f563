def fill_in(n, edges, order):
    """Fill-in of eliminating the nodes of an undirected graph in a given order.

    n:     number of nodes, labelled 0 … n-1 (int, at least 1).
    edges: list of distinct undirected edges [a, b] with a != b.
    order: the elimination order, a list holding every node exactly once.

    Eliminating a node joins every two of its remaining neighbours (adding the edges that are
    missing) and removes the node. Returns the number of edges added in total (an int).
    """
    raise NotImplementedError("TODO: eliminate the nodes in order and count the new edges")
