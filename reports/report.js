document.querySelectorAll('table.sortable th').forEach(function(th,i){
th.title='click to sort';th.onclick=function(){var tb=th.closest('table').tBodies[0];
var rows=Array.from(tb.rows),up=th.dataset.up!=='1';th.dataset.up=up?'1':'0';
rows.sort(function(a,b){var x=a.cells[i].textContent,y=b.cells[i].textContent,
p=parseFloat(x.replace(/[^0-9.eE+-]/g,'')),q=parseFloat(y.replace(/[^0-9.eE+-]/g,''));
var r=(!isNaN(p)&&!isNaN(q))?p-q:x.localeCompare(y);return up?r:-r;});
rows.forEach(function(r){tb.appendChild(r);});};});
document.querySelectorAll('input.filter').forEach(function(f){f.oninput=function(){
var t=document.getElementById(f.dataset.table),q=f.value.toLowerCase();
Array.from(t.tBodies[0].rows).forEach(function(r){
r.style.display=r.textContent.toLowerCase().indexOf(q)<0?'none':'';});};});
document.querySelectorAll('button.more').forEach(function(b){b.onclick=function(){
var t=document.getElementById(b.dataset.table);t.classList.toggle('hide-more');
b.textContent=t.classList.contains('hide-more')?'show all columns':'key columns only';};});
document.querySelectorAll('img.flip').forEach(function(im){im.title='click: flip to the reference';
im.onclick=function(){var r=document.getElementById(im.dataset.ref);if(!r)return;
if(!im.dataset.own){im.dataset.own=im.src;im.src=r.dataset.full||r.src;im.title='reference; click: back';}
else{im.src=im.dataset.own;delete im.dataset.own;im.title='click: flip to the reference';}};});
document.querySelectorAll('.film').forEach(function(fm){
var shots=fm.querySelectorAll('.film-shot'),big=fm.querySelector('.film-big'),cap=fm.querySelector('.film-cap'),
i=0,k=0,kinds=['test','ref','flip'],words=["the technique's frame",'its reference frame','their FLIP map'];
if(!shots.length||!big)return;
function show(){var d=shots[i].dataset;if(!d[kinds[k]])k=0;big.src=d[kinds[k]];big.dataset.kind=kinds[k];
big.alt='frame '+d.frame+', '+words[k];shots.forEach(function(x,j){x.classList.toggle('on',j===i);});
cap.textContent=fm.dataset.label+' \u2014 frame '+d.frame+' of '+fm.dataset.frames+', '+words[k]+': FLIP '+d.flipv+', SSIM '+d.ssim;}
function step(n){i=(i+n+shots.length)%shots.length;show();
if(shots[i].scrollIntoView)shots[i].scrollIntoView({block:'nearest',inline:'nearest'});}
function flip(){for(var t=0;t<3;t++){k=(k+1)%3;if(shots[i].dataset[kinds[k]])break;}show();}
fm.querySelector('.film-prev').onclick=function(){step(-1);};
fm.querySelector('.film-next').onclick=function(){step(1);};
fm.querySelector('.film-flip').onclick=flip;
shots.forEach(function(x,j){var im=x.querySelector('img');if(im)im.onclick=function(e){e.preventDefault();i=j;show();};});
fm.addEventListener('keydown',function(e){if(e.key==='ArrowRight')step(1);else if(e.key==='ArrowLeft')step(-1);
else if(e.key==='f'||e.key==='F')flip();else return;e.preventDefault();});
show();});
