def min_degree_order(n, edges):
    """Greedy minimum-degree elimination order (ties: the smallest index)."""
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    remaining = set(range(n))
    order = []
    while remaining:
        v = min(remaining, key=lambda u: (len(adj[u]), u))
        for a in adj[v]:
            adj[a] |= adj[v] - {a}
            adj[a].discard(v)
        adj[v].clear()
        remaining.discard(v)
        order.append(v)
    return order
