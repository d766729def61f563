# mistake: each new pair counted twice, as (a, b) and (b, a)
def _adj(n, edges):
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    return adj


def symbolic_fill(n, edges, order):
    adj = _adj(n, edges)
    fill = 0
    for v in order:
        nb = list(adj[v])
        new = [(a, b) for a in nb for b in nb if a != b and b not in adj[a]]
        fill += len(new)
        for a, b in new:
            adj[a].add(b)
        for a in nb:
            adj[a].discard(v)
    return fill
