# mistake: returns every off-diagonal nonzero of L (original edges plus fill), not only the fill
def _adj(n, edges):
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    return adj


def symbolic_fill(n, edges, order):
    adj = _adj(n, edges)
    total = 0
    for v in order:
        nb = list(adj[v])
        total += len(nb)
        for k, a in enumerate(nb):
            for b in nb[k + 1:]:
                adj[a].add(b)
                adj[b].add(a)
        for a in nb:
            adj[a].discard(v)
    return total
