# method: neighbour sets, link and count missing pairs one at a time, then remove the node
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    created = 0
    for v in order:
        for a, b in combinations(adj[v], 2):
            if b not in adj[a]:
                adj[a].add(b)
                adj[b].add(a)
                created += 1
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return created
