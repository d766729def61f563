# mistake: fill counted but never added to the graph, so later eliminations do not see it
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
        for k, a in enumerate(nb):
            for b in nb[k + 1:]:
                if b not in adj[a]:
                    fill += 1
        for a in nb:
            adj[a].discard(v)
    return fill
