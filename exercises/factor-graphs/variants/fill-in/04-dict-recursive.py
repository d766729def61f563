# method: a dict of neighbour sets, rebuilt without the eliminated node by a recursive helper
def fill_in(n, edges, order):
    graph = {v: set() for v in range(n)}
    for a, b in edges:
        graph[a].add(b)
        graph[b].add(a)

    def eliminate(graph, rest):
        if not rest:
            return 0
        v, nb = rest[0], sorted(graph[rest[0]])
        new = [(a, b) for i, a in enumerate(nb) for b in nb[i + 1:] if b not in graph[a]]
        smaller = {u: graph[u] - {v} for u in graph if u != v}
        for a, b in new:
            smaller[a] = smaller[a] | {b}
            smaller[b] = smaller[b] | {a}
        return len(new) + eliminate(smaller, rest[1:])

    return eliminate(graph, list(order))
