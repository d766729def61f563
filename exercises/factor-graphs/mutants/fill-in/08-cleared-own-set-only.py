# mistake: the eliminated node's own set is cleared but it is not removed from its neighbours' sets
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
        adj[v].clear()
    return count
