#!/usr/bin/env python3
"""A line map moved by the rigid fit of its trajectory onto the truth (docs/slam.md).

`pena eval --lines` scores a map in the mission frame, so a map drawn consistently but shifted as
a whole (the odometry's error before the first loop closure) loses the walls it shifted. This
fits the estimated trajectory onto the truth (least squares over the shared stamps: a rotation
and a translation), moves every segment of LINES.csv by the same transform and writes OUT.csv, to
be scored with `pena eval --lines OUT.csv --walls observed.csv`: what is left is the map's own
inconsistency. Prints the fit on stderr.

usage: aligned-line-map.py EST.tum TRUTH.tum LINES.csv OUT.csv
"""
import sys
import math

if len(sys.argv) != 5:
    sys.exit(__doc__)

def tum(p):
    d={}
    for l in open(p):
        if l.startswith('#') or not l.strip(): continue
        f=l.split(); d[round(float(f[0]),3)]=(float(f[1]),float(f[2]))
    return d
e=tum(sys.argv[1]); t=tum(sys.argv[2])
ks=[k for k in e if k in t]
n=len(ks)
if n < 2:
    sys.exit(f"{sys.argv[1]}: fewer than two stamps shared with {sys.argv[2]}")
mx=sum(e[k][0] for k in ks)/n; my=sum(e[k][1] for k in ks)/n
tx=sum(t[k][0] for k in ks)/n; ty=sum(t[k][1] for k in ks)/n
sxx=sum((e[k][0]-mx)*(t[k][0]-tx)+(e[k][1]-my)*(t[k][1]-ty) for k in ks)
sxy=sum((e[k][0]-mx)*(t[k][1]-ty)-(e[k][1]-my)*(t[k][0]-tx) for k in ks)
a=math.atan2(sxy,sxx); c,s=math.cos(a),math.sin(a)
def T(x,y): return (c*(x-mx)-s*(y-my)+tx, s*(x-mx)+c*(y-my)+ty)
rms=math.sqrt(sum((T(*e[k])[0]-t[k][0])**2+(T(*e[k])[1]-t[k][1])**2 for k in ks)/n)
print("rot %.2f deg shift %.3f %.3f aligned rmse %.3f" % (math.degrees(a), T(mx,my)[0]-mx, T(mx,my)[1]-my, rms), file=sys.stderr)
out=open(sys.argv[4],'w')
lines=open(sys.argv[3]).read().splitlines()
out.write(lines[0]+'\n')
for l in lines[1:]:
    f=l.split(',')
    x1,y1=T(float(f[1]),float(f[2])); x2,y2=T(float(f[3]),float(f[4]))
    out.write(','.join([f[0],'%.3f'%x1,'%.3f'%y1,'%.3f'%x2,'%.3f'%y2]+f[5:])+'\n')
