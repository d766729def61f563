# mistake: degrees counted from the edge list with repeats, so a repeated pair raises a degree
def min_degree_order(n, edges):
    adj = [[] for _ in range(n)]
    for i, j in edges:
        adj[i].append(j)
        adj[j].append(i)
    remaining = set(range(n))
    order = []
    while remaining:
        v = min(remaining, key=lambda u: (len(adj[u]), u))
        nb = set(adj[v])
        for a in nb:
            adj[a] = [u for u in adj[a] if u != v]
            for b in nb:
                if b != a and b not in adj[a]:
                    adj[a].append(b)
        adj[v] = []
        remaining.discard(v)
        order.append(v)
    return order
