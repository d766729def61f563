# method: no graph updates: the remaining neighbours of u are found by searching through eliminated variables (reachable sets)
def min_degree_order(n, edges):
    adj = [set() for _ in range(n)]
    for i, j in edges:
        adj[i].add(j)
        adj[j].add(i)
    eliminated = [False] * n

    def reach(u):
        seen = {u}
        stack = [u]
        found = set()
        while stack:
            w = stack.pop()
            for x in adj[w]:
                if x in seen:
                    continue
                seen.add(x)
                if eliminated[x]:
                    stack.append(x)
                else:
                    found.add(x)
        return found

    order = []
    for _ in range(n):
        v = min((u for u in range(n) if not eliminated[u]), key=lambda u: (len(reach(u)), u))
        eliminated[v] = True
        order.append(v)
    return order
