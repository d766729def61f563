# mistake: neighbour lists instead of sets: a repeated pair makes a variable its own "fill" partner
def symbolic_fill(n, edges, order):
    adj = [[] for _ in range(n)]
    for i, j in edges:
        adj[i].append(j)
        adj[j].append(i)
    fill = 0
    for v in order:
        nb = list(adj[v])
        for k, a in enumerate(nb):
            for b in nb[k + 1:]:
                if b not in adj[a]:
                    adj[a].append(b)
                    adj[b].append(a)
                    fill += 1
        for a in set(nb):
            adj[a] = [u for u in adj[a] if u != v]
        adj[v] = []
    return fill
