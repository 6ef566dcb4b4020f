#!/usr/bin/env python3
"""Map length by distance to the nearest true wall, and how much of the imprecise length runs
parallel (10 deg) within 0.5 m of another map segment (a wall drawn twice).
Usage: map-error-bins.py lines.csv observed.csv"""
import csv, math, sys
def load(p):
    with open(p) as f: return [(r['id'],float(r['x1']),float(r['y1']),float(r['x2']),float(r['y2'])) for r in csv.DictReader(f)]
def dist(p,s):
    _,x1,y1,x2,y2=s; dx=x2-x1; dy=y2-y1; L2=dx*dx+dy*dy
    t=0 if L2==0 else max(0,min(1,((p[0]-x1)*dx+(p[1]-y1)*dy)/L2))
    return math.hypot(p[0]-x1-t*dx,p[1]-y1-t*dy)
def ang(s): return math.atan2(s[4]-s[2],s[3]-s[1])
def adiff(a,b):
    d=abs(a-b)%math.pi; return min(d,math.pi-d)
lines=load(sys.argv[1]); walls=load(sys.argv[2])
bins=[0.1,0.2,0.3,0.5,1e9]; acc=[0]*len(bins); tot=0; dup=0
for s in lines:
    L=math.hypot(s[3]-s[1],s[4]-s[2]); n=max(1,int(L/0.05)); w=L/n
    others=[o for o in lines if o is not s and adiff(ang(o),ang(s))<0.1745]
    for i in range(n):
        p=(s[1]+(i+.5)/n*(s[3]-s[1]),s[2]+(i+.5)/n*(s[4]-s[2]))
        d=min(dist(p,wl) for wl in walls); tot+=w
        for k,b in enumerate(bins):
            if d<=b: acc[k]+=w; break
        if d>0.1:
            # a precise parallel map segment within 0.5 m covering the same stretch?
            for o in others:
                if dist(p,o)<=0.5:
                    # that other's nearest point is precise
                    dup+=w; break
print("map %.1f m; by distance to wall: <=10cm %.1f%%, 10-20 %.1f%%, 20-30 %.1f%%, 30-50 %.1f%%, >50 %.1f%%; imprecise with a parallel map segment within 0.5 m: %.1f%% of map"%(tot,*[100*a/tot for a in acc],100*dup/tot))
