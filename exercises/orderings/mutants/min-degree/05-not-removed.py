# mistake: an eliminated variable stays in its neighbours' sets, so degrees never decrease
def _adj(n, edges):
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    return adj


def min_degree_order(n, edges):
    adj = _adj(n, edges)
    remaining = set(range(n))
    order = []
    while remaining:
        v = min(remaining, key=lambda u: (len(adj[u]), u))
        for a in adj[v]:
            adj[a] |= adj[v] - {a}
        remaining.discard(v)
        order.append(v)
    return order
