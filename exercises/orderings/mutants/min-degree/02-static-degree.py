# mistake: sorted once by the original degree; degrees never updated
def _adj(n, edges):
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    return adj


def min_degree_order(n, edges):
    adj = _adj(n, edges)
    return sorted(range(n), key=lambda u: (len(adj[u]), u))
