#!/usr/bin/env python3
# SPDX-License-Identifier: MPL-2.0
"""random_compare.py -- random cutter compensation programs through rs274 and swarf.

Writes random programs (G41.1/G42.1, G17 or G18, mm or inch, G0/G1 lines, R and
IJ arcs, P turns, moves off the plane) and compares swarf's motion calls with
rs274's to 1e-4, and their errors. A developer tool (needs rs274):
  tests/gcode/ccomp/random_compare.py SEED COUNT [path/to/swarf]
"""
import random, subprocess, re, sys
import math
def prog(rng):
    g18=rng.random()<0.3
    A,B,IA,IB=("Z","X","K","I") if g18 else ("X","Y","I","J")
    L=[rng.choice(["G21","G20"])+(" G18" if g18 else "")+" G90 F100","G0 X0 Y0 Z0"]
    side=rng.choice(["G41.1","G42.1"]); d=rng.choice([0.5,1,2,3])
    L.append(f"{side} D{d}")
    x,y=0.0,0.0
    for i in range(rng.randint(3,12)):
        t=rng.random()
        nx=round(x+rng.uniform(-20,20),3); ny=round(y+rng.uniform(-20,20),3)
        if t<0.45:
            L.append(rng.choice(["G1","G1","G0"])+f" {A}{nx} {B}{ny}" + (f" Y{round(rng.uniform(-2,0),2)}" if g18 and rng.random()<0.2 else ""))
        elif t<0.55:
            L.append(("G1 Y" if g18 else "G1 Z")+f"{round(rng.uniform(-2,0),2)}"); continue
        elif t<0.7:
            r=rng.uniform(2,15); a0=rng.uniform(0,6.28); cx=x-r*math.cos(a0); cy=y-r*math.sin(a0)
            a1=a0+rng.uniform(-3,3); nx=round(cx+r*math.cos(a1),4); ny=round(cy+r*math.sin(a1),4)
            L.append(rng.choice(["G2","G3"])+f" {A}{nx} {B}{ny} {IA}{round(cx-x,4)} {IB}{round(cy-y,4)}"+(" P2" if rng.random()<0.1 else ""))
        else:
            g=rng.choice(["G2","G3"])
            ch=((nx-x)**2+(ny-y)**2)**0.5
            if ch<1e-3: continue
            r=round(ch/2*rng.uniform(1.01,3),3)*rng.choice([1,1,-1])
            L.append(f"{g} {A}{nx} {B}{ny} R{r}")
        x,y=nx,ny
    L.append("G40 G1 %s%.3f %s%.3f"%(A,x+30,B,y+30))
    L.append("M2")
    return "\n".join(L)+"\n"
def motions(text):
    out=[]
    for l in text.split("\n"):
        m=re.search(r"(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|DWELL)\(([^)]*)\)",l)
        if m: out.append((m.group(1),[float(v) for v in m.group(2).split(",")]))
    return out
def err(text):
    for l in text.split("\n"):
        if l and not l.startswith(" ") and not l.startswith("executing") and not re.match(r"^\s*\d",l): return l
    return None
SWARF = sys.argv[3] if len(sys.argv) > 3 else "build/tools/swarf"
PROG = "/tmp/swarf_random_compare.ngc"
rng=random.Random(int(sys.argv[1]) if len(sys.argv)>1 else 1)
bad=0; n=int(sys.argv[2]) if len(sys.argv)>2 else 200; errs=0
for k in range(n):
    p=prog(rng); open(PROG,"w").write(p)
    a=subprocess.run(["rs274","-g",PROG],capture_output=True,text=True); at=a.stdout+a.stderr
    b=subprocess.run([SWARF,"parse","--canon",PROG],capture_output=True,text=True); bt=b.stdout+b.stderr
    ma,mb=motions(at),motions(bt)
    ea=err(at)
    if ea: errs+=1
    ok = len(ma)==len(mb) and all(x[0]==y[0] and len(x[1])==len(y[1]) and all(abs(u-v)<=1.01e-4 for u,v in zip(x[1],y[1])) for x,y in zip(ma,mb))
    eb = b.returncode!=0
    if ok and bool(ea)!=bool(eb): ok=False
    if ok and ea and ea.split(":")[0] not in bt: ok=False
    if not ok:
        bad+=1
        if bad<=3:
            print("MISMATCH",k); print(p); print("rs274 err:",ea); print("swarf:",bt[-300:])
            for i,(x,y) in enumerate(zip(ma,mb)):
                if x!=y and not (x[0]==y[0] and all(abs(u-v)<=1.01e-4 for u,v in zip(x[1],y[1]))): print(" first diff",i,x,y); break
            print(len(ma),len(mb))
print(f"{n} programs, {errs} rejected by rs274, {bad} mismatches")
