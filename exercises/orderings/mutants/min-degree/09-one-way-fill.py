# mistake: fill added in one direction only (a knows b, b does not know a)
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
        nb = sorted(adj[v])
        for k, a in enumerate(nb):
            adj[a].discard(v)
            for b in nb[k + 1:]:
                adj[a].add(b)
        adj[v] = set()
        remaining.discard(v)
        order.append(v)
    return order
