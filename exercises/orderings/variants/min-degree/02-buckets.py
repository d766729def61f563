# method: degree buckets scanned from the lowest; the smallest index of the first non-empty bucket
def min_degree_order(n, edges):
    adj = {v: set() for v in range(n)}
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    order = []
    while adj:
        buckets = {}
        for v, nb in adj.items():
            buckets.setdefault(len(nb), []).append(v)
        v = min(buckets[min(buckets)])
        nb = adj.pop(v)
        for a in nb:
            adj[a].discard(v)
            adj[a].update(nb - {a})
        order.append(v)
    return order
