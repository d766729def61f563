# mistake: grows its working edge list as work = work + fill, starting from `edges` itself: a tuple of edges cannot be added to a list
def min_degree_order(n, edges):
    work = edges
    remaining = set(range(n))
    order = []
    while remaining:
        around = {
            v: {b for a, b in work if a == v and b in remaining}
            | {a for a, b in work if b == v and a in remaining}
            for v in remaining
        }
        v = min(remaining, key=lambda u: (len(around[u]), u))
        nb = sorted(around[v])
        work = work + [[a, b] for i, a in enumerate(nb) for b in nb[i + 1:]]
        remaining.discard(v)
        order.append(v)
    return order
