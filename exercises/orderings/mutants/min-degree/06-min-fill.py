# mistake: minimum-fill heuristic (fewest new pairs) instead of minimum degree
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

    def fill(u):
        nb = list(adj[u])
        return sum(1 for k, a in enumerate(nb) for b in nb[k + 1:] if b not in adj[a])

    while remaining:
        v = min(remaining, key=lambda u: (fill(u), u))
        for a in adj[v]:
            adj[a] |= adj[v] - {a}
            adj[a].discard(v)
        adj[v] = set()
        remaining.discard(v)
        order.append(v)
    return order
