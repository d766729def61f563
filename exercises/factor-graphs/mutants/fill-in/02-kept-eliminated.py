# mistake: eliminated nodes are never removed, so they stay neighbours of later nodes
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    count = 0
    for v in order:
        for a, b in combinations(adj[v], 2):
            if b not in adj[a]:
                adj[a].add(b)
                adj[b].add(a)
                count += 1
    return count
