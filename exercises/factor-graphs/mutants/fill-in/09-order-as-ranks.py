# mistake: reads order[k] as the step at which node k is eliminated (the inverse permutation)
from itertools import combinations


def fill_in(n, edges, order):
    adj = [set() for _ in range(n)]
    for a, b in edges:
        adj[a].add(b)
        adj[b].add(a)
    sequence = sorted(range(n), key=lambda k: order[k])
    count = 0
    for v in sequence:
        for a, b in combinations(adj[v], 2):
            if b not in adj[a]:
                adj[a].add(b)
                adj[b].add(a)
                count += 1
        for u in adj[v]:
            adj[u].discard(v)
        adj[v].clear()
    return count
