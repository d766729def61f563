def fill_in(n, edges, order):
    neighbours = {v: set() for v in range(n)}
    for a, b in edges:
        neighbours[a].add(b)
        neighbours[b].add(a)
    added = 0
    for v in order:
        around = list(neighbours[v])
        for i in range(len(around)):
            for j in range(i + 1, len(around)):
                a, b = around[i], around[j]
                if b not in neighbours[a]:
                    neighbours[a].add(b)
                    neighbours[b].add(a)
                    added += 1
        for u in around:
            neighbours[u].remove(v)
        del neighbours[v]
    return added
