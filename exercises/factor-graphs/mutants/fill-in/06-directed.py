# mistake: each edge stored in one direction only, so a node does not see neighbours listed before it
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
    count = 0
    for v in order:
        for a, b in combinations(adj[v], 2):
            if b not in adj[a] and a not in adj[b]:
                adj[a].add(b)
                count += 1
        for u in range(n):
            adj[u].discard(v)
        adj[v].clear()
    return count
