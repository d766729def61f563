# mistake: the missing pairs are counted but never added, so later eliminations do not see them
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    count = 0
    for v in order:
        count += sum(1 for a, b in combinations(adj[v], 2) if b not in adj[a])
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return count
