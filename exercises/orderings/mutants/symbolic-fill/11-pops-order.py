# mistake: consumes `order` with order.pop(0), so the caller's list is emptied (and a tuple has no pop)
def symbolic_fill(n, edges, order):
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    fill = 0
    while order:
        v = order.pop(0)
        nb = sorted(adj[v])
        for k, a in enumerate(nb):
            for b in nb[k + 1:]:
                if b not in adj[a]:
                    adj[a].add(b)
                    adj[b].add(a)
                    fill += 1
        for a in nb:
            adj[a].discard(v)
        adj[v].clear()
    return fill
