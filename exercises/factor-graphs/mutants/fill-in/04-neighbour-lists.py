# mistake: neighbour lists instead of sets: a repeated factor lists a neighbour twice, which is then "linked" to itself
def fill_in(n, edges, order):
    adj = [[] for _ in range(n)]
    for a, b in edges:
        adj[a].append(b)
        adj[b].append(a)
    count = 0
    for v in order:
        nb = adj[v]
        for i in range(len(nb)):
            for j in range(i + 1, len(nb)):
                a, b = nb[i], nb[j]
                if b not in adj[a]:
                    adj[a].append(b)
                    adj[b].append(a)
                    count += 1
        for u in nb:
            if v in adj[u]:
                adj[u].remove(v)
        adj[v] = []
    return count
