# mistake: fill-in computed as (edges ever present) - len(edges), which counts a repeated factor as an extra edge
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    seen = {frozenset(e) for e in edges}
    for v in order:
        for a, b in combinations(adj[v], 2):
            adj[a].add(b)
            adj[b].add(a)
            seen.add(frozenset((a, b)))
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return len(seen) - len(edges)
