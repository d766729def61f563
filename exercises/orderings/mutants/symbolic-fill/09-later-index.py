# mistake: "remaining neighbours" taken as neighbours with a larger index, right only for the natural order
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
        nb = [u for u in adj[v] if u > v]
        for k, a in enumerate(nb):
            for b in nb[k + 1:]:
                if b not in adj[a]:
                    adj[a].add(b)
                    adj[b].add(a)
                    fill += 1
    return fill
