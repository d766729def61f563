# mistake: returns the order reversed (last eliminated first)
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
            adj[a].discard(v)
        adj[v] = set()
        remaining.discard(v)
        order.append(v)
    return order[::-1]
