# mistake: counts every pair of remaining neighbours, including pairs already joined by an edge
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    count = 0
    for v in order:
        for a, b in combinations(adj[v], 2):
            count += 1
            adj[a].add(b)
            adj[b].add(a)
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return count
