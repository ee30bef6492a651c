"""Where a gsph step spends its time, by pass (docs/notes/performance_history.md "Profiles").

    scripts/profile.sh [SCHEME ...]     (builds target/prof with full debug info, runs perf)

Reads a `perf record` of gsph and attributes every sample to the outermost function of
gsph_core::schemes in its inlining chain (the pass: geometry_pass, solve_pairs, the
gathers), using addr2line on the binary's full debug info; prints the shares.

    python3 scripts/profile_passes.py PERF.DATA BINARY
"""
import subprocess, sys, collections, re
data, binary = sys.argv[1], sys.argv[2]
txt = subprocess.run(["perf","script","-i",data,"-F","ip","--show-mmap-events"],capture_output=True,text=True).stdout
maps=[]; ips=[]
for line in txt.splitlines():
    if "PERF_RECORD_MMAP" in line and "gsph" in line and "r-xp" in line:
        m=re.search(r"\[(0x[0-9a-f]+)\((0x[0-9a-f]+)\) @ (0x[0-9a-f]+|0) ",line)
        if m: maps.append((int(m.group(1),16),int(m.group(2),16),int(m.group(3),16)))
    else:
        s=line.strip()
        if re.fullmatch(r"[0-9a-f]+",s): ips.append(int(s,16))
start,length,pgoff=maps[0]
ph=subprocess.run(["readelf","-lW",binary],capture_output=True,text=True).stdout
for l in ph.splitlines():
    f=l.split()
    if f and f[0]=="LOAD" and "E" in f[-2:-1]+f[-3:-1]:
        p_off=int(f[1],16); p_vaddr=int(f[2],16)
delta=p_vaddr-p_off
cnt=collections.Counter()
for ip in ips:
    if start<=ip<start+length: cnt[ip-start+pgoff+delta]+=1
    else: cnt[None]+=1
total=sum(cnt.values())
addrs=[a for a in cnt if a is not None]
# one address per call, separated by a sentinel address 0
args=[]
for a in addrs: args += [hex(a), "0x0"]
out=subprocess.run(["addr2line","-f","-i","-C","-e",binary],input="\n".join(args),capture_output=True,text=True).stdout.splitlines()
# parse: groups end at the sentinel's output "??" "??:0"
groups=[]; cur=[]
i=0
while i < len(out):
    fn=out[i]; loc=out[i+1] if i+1<len(out) else ""
    i+=2
    if fn=="??" and loc.startswith("??"):
        groups.append(cur); cur=[]
    else:
        cur.append((fn,loc))
by=collections.Counter()
for a,g in zip(addrs,groups):
    name="other"
    # outermost frame in gsph_core::schemes that is a pass (closure of a fn in schemes)
    for fn,loc in reversed(g):
        m=re.search(r"gsph_core::schemes::(\w+)::(\w+)",fn)
        if m and m.group(2) not in ("for_each_pair",):
            name=m.group(1)+"::"+m.group(2); break
    if name=="other":
        # a vectorised row (gsph_core::simd, entered through its level's function): the
        # outermost simd frame, so that its inlined lane arithmetic counts to the row
        for fn,loc in reversed(g):
            m=re.search(r"gsph_core::simd::(\w+)::(\w+)",fn)
            if m: name="simd::"+m.group(1)+"::"+m.group(2); break
    if name=="other":
        for fn,loc in g:
            m=re.search(r"(gsph\w*::[\w:]+)",fn)
            if m: name=m.group(1); break
    by[name]+=cnt[a]
by["outside gsph"]+=cnt[None]
for k,v in by.most_common(14):
    print("%5.1f %%  %s"%(100*v/total,k))
